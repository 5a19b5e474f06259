// Tests for sim/table (CSV quoting, Markdown and console alignment), the
// number formatting helpers, and sim/ticks.
#include "sim/util/table.h"
#include "sim/plot/ticks.h"

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

namespace {

std::vector<std::string> lines_of(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

}  // namespace

TEST_CASE("output table: CSV quotes commas, quotes and newlines (RFC 4180)") {
    rtc::Table t({"name", "value"});
    t.add_row({"plain", "1"});
    t.add_row({"a,b", "say \"hi\""});
    t.add_row({"two\nlines", ""});
    CHECK(t.to_csv() == "name,value\r\nplain,1\r\n\"a,b\",\"say \"\"hi\"\"\"\r\n\"two\nlines\",\r\n");
    CHECK_THROWS_AS(t.add_row({"only one"}), std::invalid_argument);
}

TEST_CASE("output table: Markdown pads columns and right-aligns numbers") {
    rtc::Table t({"method", "clocks", "speedup"});
    t.add_row({"ref", "1,234,567", "1.00x"});
    t.add_row({"obb|x", "89", "13.9x"});
    const std::vector<std::string> l = lines_of(t.to_markdown());
    REQUIRE(l.size() == 4);
    CHECK(l[0] == "| method |    clocks | speedup |");
    CHECK(l[1] == "| ------ | --------: | ------: |");
    CHECK(l[2] == "| ref    | 1,234,567 |   1.00x |");
    CHECK(l[3] == "| obb\\|x |        89 |   13.9x |");
    CHECK(t.is_numeric_column(1));
    CHECK_FALSE(t.is_numeric_column(0));
}

TEST_CASE("output table: console output aligns columns under a rule") {
    rtc::Table t({"phase", "time"});
    t.add_row({"build obb", "1.5 s"});
    t.add_row({"trace", "12.25 s"});
    const std::vector<std::string> l = lines_of(t.to_console());
    REQUIRE(l.size() == 4);
    CHECK(l[0] == "phase         time");
    CHECK(l[1] == "---------  -------");
    CHECK(l[2] == "build obb    1.5 s");
    CHECK(l[3] == "trace      12.25 s");
}

TEST_CASE("output table: looks_numeric") {
    for (const char* s : {"1", "-2.5", "1,234", "1.23x", "12 KiB", "5%", "3e-05", ".5"}) CHECK(rtc::looks_numeric(s));
    for (const char* s : {"", "x", "3D", "ref", "-", "1,,2", "nan"}) CHECK_FALSE(rtc::looks_numeric(s));
}

TEST_CASE("output format: significant digits, thousands, speedups, bytes, durations") {
    CHECK(rtc::format_sig(1.2, 3) == "1.20");
    CHECK(rtc::format_sig(1234.5, 3) == "1230");
    CHECK(rtc::format_sig(0.00123456, 3) == "0.00123");
    CHECK(rtc::format_sig(9.996, 3) == "10.0");
    CHECK(rtc::format_sig(-42.0, 2) == "-42");
    CHECK(rtc::format_sig(1e-7, 2) == "1.0e-07");
    CHECK(rtc::format_sig(0.0) == "0");
    CHECK(rtc::format_sig(std::nan("")) == "nan");
    CHECK(rtc::format_fixed(2.345, 1) == "2.3");
    CHECK(rtc::format_thousands(0) == "0");
    CHECK(rtc::format_thousands(999) == "999");
    CHECK(rtc::format_thousands(1234567) == "1,234,567");
    CHECK(rtc::format_thousands(-1000) == "-1,000");
    CHECK(rtc::format_speedup(1.234) == "1.23x");
    CHECK(rtc::format_speedup(12.0) == "12.0x");
    CHECK(rtc::format_bytes(512) == "512 B");
    CHECK(rtc::format_bytes(1536) == "1.50 KiB");
    CHECK(rtc::format_bytes(3ull << 20) == "3.00 MiB");
    CHECK(rtc::format_bytes(1ull << 30) == "1.00 GiB");
    CHECK(rtc::format_duration(0.5) == "500 ms");
    CHECK(rtc::format_duration(12.34) == "12.3 s");
    CHECK(rtc::format_duration(75.2) == "1m15s");
    CHECK(rtc::format_duration(3725.0) == "1h02m");
}

TEST_CASE("output ticks: nice linear and log ticks with labels") {
    const std::vector<rtc::Tick> lin = rtc::linear_ticks(0.0, 10.0, 5);
    REQUIRE(lin.size() == 6);
    CHECK(lin[1].value == doctest::Approx(2.0));
    CHECK(lin[5].label == "10");
    const std::vector<rtc::Tick> frac = rtc::linear_ticks(0.03, 0.97, 5);
    REQUIRE(frac.size() >= 4);
    CHECK(frac.front().label == "0.2");
    CHECK(rtc::linear_ticks(-1.0, 1.0, 4)[2].label == "0.0");  // never "-0.0"
    CHECK(rtc::format_tick(12000, 1000) == "12k");
    CHECK(rtc::format_tick(3500000, 500000) == "3.5M");
    const std::vector<rtc::Tick> lg = rtc::log_ticks(1.0, 1000.0);
    REQUIRE(lg.size() == 4);
    CHECK(lg[3].label == "1000");
    const std::vector<rtc::Tick> few = rtc::log_ticks(1.0, 20.0);  // under two decades: 1 2 5 10 20
    REQUIRE(few.size() == 5);
    CHECK(few[1].label == "2");
    CHECK(rtc::log_ticks(0.0, 10.0).empty());
    CHECK(rtc::linear_ticks(2.0, 1.0).empty());
}

}  // namespace RTCSIM_TEST_FILE
