#include "sim/methods/method.h"

#include <mutex>
#include <stdexcept>

namespace rtc {

// The built-in methods, one line each: X(name) refers to `MethodEntry
// name_method()` defined in sim/methods/name.cpp.
#define RTCSIM_BUILTIN_METHODS(X) \
    X(ref)                        \
    X(obb)                        \
    X(leaf_obb)                   \
    X(split)                      \
    X(lss)                        \
    X(dots)                       \
    X(obb_nodes)                  \
    X(obb_quantized)              \
    X(aabb_quantized)             \
    X(cluster)

#define RTCSIM_DECLARE(name) MethodEntry name##_method();
RTCSIM_BUILTIN_METHODS(RTCSIM_DECLARE)
#undef RTCSIM_DECLARE

namespace {

std::vector<MethodEntry>& registry() {
    static std::vector<MethodEntry> methods = [] {
        std::vector<MethodEntry> v;
#define RTCSIM_ADD(name) v.push_back(name##_method());
        RTCSIM_BUILTIN_METHODS(RTCSIM_ADD)
#undef RTCSIM_ADD
        return v;
    }();
    return methods;
}

std::mutex& registry_mutex() {
    static std::mutex m;
    return m;
}

}  // namespace

const std::vector<MethodEntry>& registered_methods() { return registry(); }

const MethodEntry* find_method(std::string_view name) {
    for (const MethodEntry& m : registry())
        if (m.info.name == name) return &m;
    return nullptr;
}

void register_method(MethodEntry entry) {
    const std::lock_guard lock(registry_mutex());
    if (entry.info.name.empty()) throw std::invalid_argument("register_method: empty method name");
    if (!entry.instance_count || !entry.build)
        throw std::invalid_argument("register_method: " + entry.info.name + ": missing instance_count or build");
    if (find_method(entry.info.name))
        throw std::invalid_argument("register_method: a method named '" + entry.info.name + "' exists");
    registry().push_back(std::move(entry));
}

std::string not_applicable_reason(const MethodEntry& entry, const Geometry& g) {
    return entry.not_applicable ? entry.not_applicable(g) : std::string();
}

std::string method_names_list() {
    std::string s;
    for (const MethodEntry& m : registry()) s += (s.empty() ? "" : ", ") + m.info.name;
    return s;
}

}  // namespace rtc
