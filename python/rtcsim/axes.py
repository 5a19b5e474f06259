"""A sweep's axes, found as the CLI's sweep plots find them
(sim/report/sweep_plots.cpp is the reference): the figures of rtcsim.plot
place runs on them, so a paired axis such as {count, radius} is one axis
with one series, as in the CLI's SVG, not two axes of single points.
`runs` are Reports (report.json)."""
import json
import os


def _value_key(v):
    return json.dumps(v, sort_keys=True)


def _short(v):
    """A value as the CLI's sweep plots write it: preset paths by their stem."""
    if isinstance(v, str):
        return os.path.splitext(os.path.basename(v))[0] if v.endswith(".json") or "/" in v else v
    if isinstance(v, float):  # as written in the config (0.1, not 0.100), unless long
        return repr(v) if len(repr(v)) <= 8 else f"{v:.3g}"
    return json.dumps(v)


def sweep_axes(runs):
    """The sweep's axes as the CLI's sweep plots find them
    (sim/report/sweep_plots.cpp, the reference): keys grouped while two
    groups do not take every combination of their values, so the members of
    a paired list ({count, radius}) are one axis, not two. Each axis is a
    dict: keys, key (file name: the members' common prefix), name ("count,
    radius"), values (distinct tuples, first-seen order), x (per value: the
    first numeric member that tells the values apart, else the sweep order),
    numeric, tick and legend (per value)."""
    def tuples(keys):
        return list(dict.fromkeys(tuple(_value_key(r.sweep_point.get(k)) for k in keys) for r in runs))

    groups = [[k] for k in dict.fromkeys(k for r in runs for k in r.sweep_point) if len(tuples([k])) >= 2]
    merged = True
    while merged:
        merged = False
        for i in range(len(groups)):
            for j in range(i + 1, len(groups)):
                if len(tuples(groups[i] + groups[j])) < len(tuples(groups[i])) * len(tuples(groups[j])):
                    groups[i] += groups.pop(j)
                    merged = True
                    break
            if merged:
                break
    axes = []
    for keys in groups:
        values = [tuple(json.loads(v) for v in t) for t in tuples(keys)]
        varying = [k for k in range(len(keys)) if len({_value_key(t[k]) for t in values}) > 1
                   and all(not isinstance(t[k], (dict, list)) for t in values)]
        last = [k.rsplit(".", 1)[-1] for k in keys]
        named = [k for k in varying if last[k] == "name"]
        varying = named[:1] or varying
        key = keys[0]
        for k in keys:
            while key and k != key and not k.startswith(key + "."):
                key = key.rsplit(".", 1)[0] if "." in key else ""
        if len(keys) == 1:
            name = keys[0]
        else:
            name = ", ".join(key if last[k] == "name" else last[k] for k in varying) or key
        key = key or name
        ticks, legends = [], []
        for i, t in enumerate(values):
            parts = [(k, _short(t[k])) for k in varying if t[k] is not None]
            ticks.append(", ".join(v for _, v in parts) or f"#{i}")
            legends.append(", ".join(f"{keys[k] if len(keys) == 1 else key if last[k] == 'name' else last[k]}={v}"
                                     for k, v in parts) or f"#{i}")
        x, numeric = list(range(len(values))), False
        for k in varying:
            xs = [t[k] for t in values if isinstance(t[k], (int, float)) and not isinstance(t[k], bool)]
            if len(xs) == len(values) and len(set(xs)) == len(xs):
                x, numeric = xs, True
                break
        axes.append({"keys": keys, "key": key, "name": name, "values": values, "x": x, "numeric": numeric,
                     "tick": ticks, "legend": legends})
    return axes


def axis_index(axis, run):
    """The index of `run`'s value on `axis`."""
    return axis["values"].index(tuple(run.sweep_point.get(k) for k in axis["keys"]))
