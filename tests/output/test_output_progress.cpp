// Tests for sim/progress: silent when disabled, plain lines when not a TTY,
// in-place redraws on a TTY, exact counts under concurrent advance().
#include "sim/util/progress.h"

#include <doctest/doctest.h>

#include <cstdio>
#include <string>
#include <thread>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

namespace {

std::string read_all(std::FILE* f) {
    std::fflush(f);
    std::rewind(f);
    std::string s;
    for (int c; (c = std::fgetc(f)) != EOF;) s += static_cast<char>(c);
    return s;
}

std::size_t count(const std::string& s, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
    return n;
}

}  // namespace

TEST_CASE("output progress: disabled prints nothing but still counts") {
    std::FILE* f = std::tmpfile();
    REQUIRE(f != nullptr);
    {
        rtc::Progress p("trace ref", 100, false, f, true);
        for (int i = 0; i < 100; ++i) p.advance();
        CHECK(p.done() == 100);
        p.finish();
    }
    CHECK(read_all(f).empty());
    std::fclose(f);
}

TEST_CASE("output progress: not a TTY prints start, quarter and final lines only") {
    std::FILE* f = std::tmpfile();
    REQUIRE(f != nullptr);
    {
        rtc::Progress p("build obb", 100, true, f, false);
        for (int i = 0; i < 100; ++i) p.advance();
    }  // the destructor finishes
    const std::string out = read_all(f);
    std::fclose(f);
    CHECK(count(out, "\n") == 5);
    CHECK(out.rfind("build obb: started (100)\n", 0) == 0);
    CHECK(out.find("build obb: 25% (25/100)") != std::string::npos);
    CHECK(out.find("build obb: 75% (75/100)") != std::string::npos);
    CHECK(out.find("build obb: done 100 in ") != std::string::npos);
    CHECK(out.find('\r') == std::string::npos);
}

TEST_CASE("output progress: TTY redraws in place and ends with one newline") {
    std::FILE* f = std::tmpfile();
    REQUIRE(f != nullptr);
    rtc::Progress p("trace", 10, true, f, true);
    p.advance(10);
    p.finish();
    p.finish();  // idempotent
    const std::string out = read_all(f);
    std::fclose(f);
    CHECK(out.front() == '\r');
    CHECK(count(out, "\n") == 1);
    CHECK(out.find("[##############################] 100% 10/10 done in") != std::string::npos);
}

TEST_CASE("output progress: concurrent advance counts exactly") {
    std::FILE* f = std::tmpfile();
    REQUIRE(f != nullptr);
    rtc::Progress p("threads", 40000, true, f, true);
    std::vector<std::thread> workers;
    for (int t = 0; t < 4; ++t)
        workers.emplace_back([&p] {
            for (int i = 0; i < 10000; ++i) p.advance();
        });
    for (auto& w : workers) w.join();
    CHECK(p.done() == 40000);
    p.finish();
    CHECK(read_all(f).find("40,000/40,000 done in") != std::string::npos);
    std::fclose(f);
}

}  // namespace RTCSIM_TEST_FILE
