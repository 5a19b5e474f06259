#include "sim/hardware/sm_model.h"

#include "sim/util/json_reader.h"

#include <algorithm>
#include <stdexcept>

namespace rtc {

int SmModel::pipeline_registers(std::string_view program) const {
    const std::string_view key = program.empty() ? std::string_view("shader") : program;
    for (const auto& [name, n] : registers)
        if (name == key) return n;
    throw std::invalid_argument("the sm block lists no registers for the pipeline \"" + std::string(key) + "\"");
}

int resident_warps(const SmModel& sm, int registers, int warp_width) {
    const int unit = std::max(sm.allocation_unit, 1);
    const int per_warp = (registers * warp_width + unit - 1) / unit * unit;
    const int partitions = std::max(sm.partitions, 1);
    const int by_registers = per_warp > 0 ? partitions * (sm.registers_per_sm / partitions / per_warp) : sm.max_warps;
    return std::clamp(by_registers, 1, sm.max_warps);
}

Roofline roofline(const SmModel& sm, std::string_view program, int warp_width) {
    Roofline r;
    if (!sm.enabled) return r;
    r.enabled = true;
    r.registers = sm.pipeline_registers(program);
    r.warps = resident_warps(sm, r.registers, warp_width);
    r.latency_per_issue = sm.latency_per_issue;
    r.rt_unit_lanes = sm.rt_unit_lanes;
    return r;
}

std::string pipeline_program(PrimitiveKind kind, PhantomProgram program, bool runs_programs) {
    if (!runs_programs) return {};
    if (kind != PrimitiveKind::Phantom) return std::string(kind_name(kind));
    return program == PhantomProgram::Paper ? "phantom_paper" : "phantom_bracketed";
}

namespace {

bool entry_enabled(const JsonReader& r) {
    const JsonReader e = r.child("enabled");
    e.allow_only({"value", "source"});
    (void)e.string("source", std::nullopt);
    return e.boolean("value", std::nullopt);
}

}  // namespace

SmModel parse_sm_model(const JsonReader& r, const SmModel& base) {
    r.allow_only({"enabled", "registers_per_sm", "max_warps", "allocation_unit", "partitions", "registers",
                   "latency_per_issue", "rt_unit_lanes"});
    SmModel m = base;
    m.enabled = true;
    if (r.has("enabled")) {
        // A derived preset of another machine turns its base's SM off
        // rather than inherit register counts measured for another chip.
        m.enabled = entry_enabled(r);
        if (!m.enabled) return m;
    }
    const auto entry = [&](std::string_view key) {
        const JsonReader e = r.child(key);
        e.allow_only({"value", "source"});
        std::erase_if(m.sources, [&](const auto& s) { return s.first == key; });
        m.sources.emplace_back(std::string(key), e.string("source", std::nullopt));
        return e;
    };
    if (r.has("registers_per_sm"))
        m.registers_per_sm = static_cast<int>(entry("registers_per_sm").integer("value", std::nullopt, 1024, 1 << 20));
    if (r.has("max_warps")) m.max_warps = static_cast<int>(entry("max_warps").integer("value", std::nullopt, 1, 256));
    if (r.has("allocation_unit"))
        m.allocation_unit = static_cast<int>(entry("allocation_unit").integer("value", std::nullopt, 1, 4096));
    if (r.has("partitions")) m.partitions = static_cast<int>(entry("partitions").integer("value", std::nullopt, 1, 64));
    if (r.has("latency_per_issue"))
        m.latency_per_issue = entry("latency_per_issue").number("value", std::nullopt, 1.0, 1000.0);
    if (r.has("rt_unit_lanes")) m.rt_unit_lanes = entry("rt_unit_lanes").number("value", std::nullopt, 1.0, 1e6);
    if (r.has("registers")) {
        const JsonReader e = entry("registers");
        const JsonReader v = e.child("value");
        m.registers.clear();
        for (const auto& [name, n] : v.json().items()) {
            const long long regs = v.integer(name, std::nullopt, 1, 255);  // CC 7.x: at most 255 per thread
            m.registers.emplace_back(name, static_cast<int>(regs));
        }
    }
    if (std::none_of(m.registers.begin(), m.registers.end(), [](const auto& p) { return p.first == "shader"; }))
        r.fail("registers", "lists no registers for \"shader\" (ray generation and shading, in every pipeline)");
    return m;
}

}  // namespace rtc
