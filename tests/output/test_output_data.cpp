// Tidy data outputs of `simulate` (in process, through run_all): the .npy
// writer and reader, results.csv (raw numbers, one row per point x method x
// preset, one column per sweep value), the sweep's combined report.json, and
// the per-pixel / per-ray arrays whose sums equal report.json's totals.
#include "core/events.h"
#include "sim/app/run_all.h"
#include "sim/report/npy.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

const std::string kTiny = "tests/configs/tiny.json";

std::string out_dir(const std::string& name) {
    const fs::path p = fs::path(RTCSIM_BINARY_DIR) / "e2e" / ("data_" + name);
    fs::remove_all(p);
    return p.string();
}

void run(const std::string& out, std::vector<std::string> sets) {
    CliOptions cli;
    cli.config = kTiny;
    cli.out = out;
    cli.quiet = true;
    cli.threads = 2;
    cli.sets = std::move(sets);
    REQUIRE(run_all(cli) == 0);
}

nlohmann::json json_at(const fs::path& p) { return nlohmann::json::parse(read_text_file(p.string())); }

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> row(1);
        for (const char c : line) {
            if (c == ',') row.emplace_back();
            else row.back() += c;
        }
        rows.push_back(row);
    }
    return rows;
}

bool parses_as_number(const std::string& s) {
    double v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && end == s.data() + s.size();
}

// Sum over the leading axes of an array of shape (..., E) per event, or of all items.
std::vector<double> column_sums(const NpyArray& a, std::size_t columns) {
    std::vector<double> sums(columns, 0.0);
    for (std::size_t i = 0; i < a.size(); ++i) sums[i % columns] += a.as_double(i);
    return sums;
}

// Every method's counts and cycles arrays of a run directory against its report.json.
void check_arrays(const fs::path& dir, bool image) {
    const nlohmann::json report = json_at(dir / "report.json");
    const nlohmann::json side = json_at(dir / "arrays.json");
    REQUIRE(side["events"].size() == kEventCount);
    CHECK(side["events"][0] == std::string(kEventNames[0]));
    for (const auto& item : report["methods"].items()) {
        const std::string name = item.key();  // (clang 14 cannot capture a structured binding)
        const nlohmann::json& m = item.value();
        CAPTURE(name);
        const NpyArray counts = read_npy((dir / ("counts_" + name + ".npy")).string());
        CHECK(counts.type == NpyType::U32);
        REQUIRE(counts.shape.size() == (image ? 3u : 2u));
        CHECK(counts.shape.back() == kEventCount);
        if (image) {
            CHECK(counts.shape[0] == report["camera"]["height"].get<std::size_t>());
            CHECK(counts.shape[1] == report["camera"]["width"].get<std::size_t>());
        } else {
            CHECK(counts.shape[0] == m["rays"].get<std::size_t>());
        }
        const std::vector<double> sums = column_sums(counts, kEventCount);
        for (std::size_t e = 0; e < kEventCount; ++e)
            CHECK(sums[e] == m["events"][std::string(kEventNames[e])]["total"].get<double>());
        for (const auto& priced : m["cycles"].items()) {
            const std::string preset = priced.key();
            const nlohmann::json& c = priced.value();
            CAPTURE(preset);
            const nlohmann::json& entry = side["methods"][name]["cycles"][preset];
            if (!entry.contains("file")) {
                CHECK(!image);  // only ray lists under a warp preset have no per-ray cycles
                continue;
            }
            const NpyArray cycles = read_npy((dir / entry["file"].get<std::string>()).string());
            CHECK(cycles.type == NpyType::F64);
            CHECK(cycles.shape.size() == (image ? 2u : 1u));
            const double total = column_sums(cycles, 1)[0];
            CHECK(total == doctest::Approx(c["total"].get<double>()).epsilon(1e-5));
            CHECK(total > 0.0);
        }
    }
}

}  // namespace

TEST_CASE("output npy: header layout, round trip, and errors naming the file") {
    const std::string h = npy_header(NpyType::U32, {3, 2, 5});
    CHECK(h.size() % 64 == 0);
    CHECK(h.compare(0, 6, "\x93NUMPY") == 0);
    CHECK(h.find("'descr': '<u4', 'fortran_order': False, 'shape': (3, 2, 5), }") != std::string::npos);
    CHECK(h.back() == '\n');
    CHECK(npy_header(NpyType::F64, {7}).find("'shape': (7,), }") != std::string::npos);
    const fs::path dir = out_dir("npy");
    fs::create_directories(dir);
    const std::vector<double> values{1.5, -2.0, 1e300, 0.0, 3.25, 7.0};
    write_npy((dir / "a.npy").string(), {2, 3}, values);
    const NpyArray a = read_npy((dir / "a.npy").string());
    CHECK(a.type == NpyType::F64);
    CHECK(a.shape == std::vector<std::size_t>{2, 3});
    for (std::size_t i = 0; i < values.size(); ++i) CHECK(a.as_double(i) == values[i]);
    const std::vector<std::uint32_t> ints{4000000000u, 1, 2};
    write_npy((dir / "b.npy").string(), NpyType::U32, {3}, ints.data());
    CHECK(read_npy((dir / "b.npy").string()).as_u64(0) == 4000000000u);
    std::ofstream((dir / "bad.npy").string(), std::ios::binary) << "NUMPY";
    CHECK_THROWS_WITH_AS(static_cast<void>(read_npy((dir / "bad.npy").string())), doctest::Contains("bad.npy: not a .npy file"),
                         InputError);
    const std::string whole = read_text_file((dir / "a.npy").string());
    std::ofstream((dir / "short.npy").string(), std::ios::binary) << whole.substr(0, whole.size() - 8);
    CHECK_THROWS_WITH_AS(static_cast<void>(read_npy((dir / "short.npy").string())), doctest::Contains("short.npy: 40 data bytes, shape needs 48"),
                         InputError);
}

TEST_CASE("output data: a paired sweep gives tidy results.csv, a combined report.json and arrays summing to totals") {
    const std::string out = out_dir("sweep");
    run(out, {"sweep={\"scene\":[{\"count\":1,\"radius\":0.1},{\"count\":20,\"radius\":0.01}],\"scene.tilt_deg\":[0,45]}",
              "cost=[\"../../configs/hw/turing-calibrated.json\",\"../../configs/hw/turing-per-ray-guess.json\"]",
              "output={\"images\":false}", "workload.width=20", "workload.height=16"});
    const auto rows = csv_rows(read_text_file(out + "/results.csv"));
    REQUIRE(rows.size() == 1 + 4 * 2 * 2);  // header + points x methods x presets
    const std::vector<std::string>& header = rows[0];
    const auto col = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        REQUIRE(it != header.end());
        return static_cast<std::size_t>(it - header.begin());
    };
    const std::size_t count = col("scene.count"), radius = col("scene.radius"), tilt = col("scene.tilt_deg");
    const std::size_t speedup = col("speedup"), cycles = col("cycles"), per_ray = col("cycles_per_ray"), rays = col("rays");
    const std::size_t preset = col("cost_preset"), execution = col("execution"), method = col("method");
    std::map<std::string, int> presets;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const auto& r = rows[i];
        REQUIRE(r.size() == header.size());
        for (const std::size_t c : {count, radius, tilt, speedup, cycles, per_ray, rays, col("memory_bytes"),
                                    col("memory_mib"), col("is_calls_per_ray"), col("memory_overhead_percent")})
            CHECK_MESSAGE(parses_as_number(r[c]), header[c] << " = '" << r[c] << "'");
        CHECK(std::stod(r[per_ray]) == doctest::Approx(std::stod(r[cycles]) / std::stod(r[rays])));
        if (r[method] == "ref") CHECK(std::stod(r[speedup]) == 1.0);
        ++presets[r[preset] + "/" + r[execution]];
    }
    CHECK(presets["turing-calibrated/warp"] == 8);
    CHECK(presets["turing-per-ray-guess/per_ray"] == 8);
    CHECK(rows[1][count] == "1");
    CHECK(rows[1][radius] == "0.1");

    // The combined report: every point with its values, directory and report.
    const nlohmann::json all = json_at(fs::path(out) / "report.json");
    REQUIRE(all["points"].size() == 4);
    CHECK(all["axes"] == nlohmann::json::array({"scene.count", "scene.radius", "scene.tilt_deg"}));
    for (const auto& p : all["points"]) {
        const fs::path dir = fs::path(out) / p["dir"].get<std::string>();
        CHECK(json_at(dir / "report.json")["methods"] == p["report"]["methods"]);
        CHECK(p["values"] == p["report"]["sweep_point"]);
        check_arrays(dir, true);
    }
    // speedup column = the report's speedup under that preset.
    const nlohmann::json& s = all["points"][3]["report"]["speedup_over_ref"]["obb"];
    bool found = false;
    for (std::size_t i = 1; i < rows.size(); ++i)
        if (rows[i][col("point")] == "3" && rows[i][method] == "obb" && rows[i][preset] == "turing-per-ray-guess") {
            CHECK(std::stod(rows[i][speedup]) == doctest::Approx(s["turing-per-ray-guess"].get<double>()));
            found = true;
        }
    CHECK(found);
}

TEST_CASE("output data: a ray-file run writes per-ray counts that sum to the totals") {
    const std::string first = out_dir("rays_source");
    run(first, {"output={\"images\":false,\"rays\":true}", "workload.width=12", "workload.height=10"});
    check_arrays(first, true);
    const std::string out = out_dir("rays");
    run(out, {"workload={\"type\":\"rays\",\"rays_file\":\"" + first + "/rays.bin\"}",
              "cost=[\"../../configs/hw/turing-calibrated.json\",\"../../configs/hw/turing-per-ray-guess.json\"]",
              "output.images=false"});
    CHECK(!fs::exists(fs::path(out) / "render.png"));
    check_arrays(out, false);
    const nlohmann::json side = json_at(fs::path(out) / "arrays.json");
    CHECK(side["methods"]["ref"]["cycles"]["turing-calibrated"].contains("n/a"));
    CHECK(side["methods"]["ref"]["cycles"]["turing-per-ray-guess"]["file"] == "cycles_ref_turing-per-ray-guess.npy");
    // output.arrays=false writes none.
    const std::string none = out_dir("no_arrays");
    run(none, {"output={\"images\":false,\"arrays\":false}", "workload.width=8", "workload.height=8"});
    CHECK(!fs::exists(fs::path(none) / "arrays.json"));
    CHECK(!fs::exists(fs::path(none) / "counts_ref.npy"));
    CHECK(fs::exists(fs::path(none) / "results.csv"));
}

TEST_CASE("output data: a method that cannot run gives rows with empty numbers and a reason") {
    const std::string out = out_dir("na");
    run(out, {"methods=[\"ref\",\"obb\",\"lss\"]", "primitives.kind=phantom", "output={\"images\":false}",
              "workload.width=8", "workload.height=8"});
    const auto rows = csv_rows(read_text_file(out + "/results.csv"));
    const std::vector<std::string>& header = rows[0];
    const auto col = [&](const std::string& name) {
        return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
    };
    REQUIRE(col("reason") < header.size());
    int na = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const auto& r = rows[i];
        if (r[col("method")] != "lss") {
            CHECK(r[col("reason")].empty());
            CHECK(r[col("rays")].ends_with(".0"));  // whole numbers beside a gap: read as floats
            CHECK(parses_as_number(r[col("rays")]));
            continue;
        }
        ++na;
        CHECK(r[col("reason")].find("not linear swept spheres") != std::string::npos);
        for (const char* c : {"rays", "cycles", "cycles_per_ray", "speedup", "memory_bytes", "memory_overhead_percent"})
            CHECK_MESSAGE(r[col(c)].empty(), c);
    }
    CHECK(na == 1);
    CHECK(rows[1][col("primitive_count")] == "60");  // no gap in this column: an integer
}

}  // namespace RTCSIM_TEST_FILE
