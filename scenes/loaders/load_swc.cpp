// SWC neuron morphology: "id type x y z radius parent" per node, parent -1
// (any negative) for a root. The trees are cut into unbranched chains, each
// a strand: a chain runs from a root or branch node down through single-child
// nodes to a leaf; at a branch the first child continues the chain and every
// other child starts a new chain at the branch node. So every parent-child
// pair is exactly one segment and segments = nodes - roots. Nodes given with
// no parent and no child (isolated somas) make no segment and are skipped.
#include "scenes/loaders/file_bytes.h"
#include "scenes/loaders/loaders.h"
#include "scenes/generators/strand_builder.h"
#include "scenes/loaders/text_lines.h"

#include <unordered_map>
#include <utility>

namespace rtc {

namespace {
struct SwcNode {
    long long id;
    long long parent;
    Vec3 pos;
    float radius;
    std::size_t line;
    std::vector<std::uint32_t> children;
};
}  // namespace

LoadedCurves load_swc(const std::filesystem::path& file) {
    const std::vector<std::uint8_t> bytes = read_file_bytes(file);
    TextLines text(std::string(bytes.begin(), bytes.end()), file.string());
    std::vector<SwcNode> nodes;
    std::unordered_map<long long, std::uint32_t> index_of;
    while (text.next()) {
        if (text.blank()) continue;
        if (text.tokens().size() != 7)
            text.fail("expected 7 fields \"id type x y z radius parent\", got " +
                      std::to_string(text.tokens().size()));
        SwcNode n{text.number<long long>(0, "id"),
                  text.number<long long>(6, "parent"),
                  Vec3(text.number<float>(2, "x"), text.number<float>(3, "y"),
                       text.number<float>(4, "z")),
                  text.number<float>(5, "radius"),
                  text.line_number(),
                  {}};
        (void)text.number<double>(1, "type");
        if (!index_of.emplace(n.id, static_cast<std::uint32_t>(nodes.size())).second)
            text.fail("duplicate node id " + std::to_string(n.id));
        nodes.push_back(std::move(n));
    }
    const std::string name = file.string();
    std::vector<std::uint32_t> roots;
    for (std::uint32_t i = 0; i < nodes.size(); ++i) {
        if (nodes[i].parent < 0) {
            roots.push_back(i);
            continue;
        }
        const auto it = index_of.find(nodes[i].parent);
        if (it == index_of.end())
            throw InputError(name + ": line " + std::to_string(nodes[i].line) + ": node " +
                             std::to_string(nodes[i].id) + " has parent " +
                             std::to_string(nodes[i].parent) + ", which does not exist");
        nodes[it->second].children.push_back(i);
    }

    LoadedCurves out;
    out.has_radius = true;
    StrandBuilder build(out.strands, name);
    std::vector<bool> visited(nodes.size(), false);
    // Pending chains: (start node, first child). Depth-first, file order.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pending;
    for (std::uint32_t root : roots) {
        visited[root] = true;
        const auto& kids = nodes[root].children;
        for (std::size_t c = kids.size(); c-- > 0;) pending.emplace_back(root, kids[c]);
        while (!pending.empty()) {
            auto [from, node] = pending.back();
            pending.pop_back();
            build.add_point(nodes[from].pos, nodes[from].radius, at_line(nodes[from].line));
            for (;;) {
                visited[node] = true;
                build.add_point(nodes[node].pos, nodes[node].radius, at_line(nodes[node].line));
                const auto& next = nodes[node].children;
                if (next.empty()) break;
                for (std::size_t c = next.size(); c-- > 1;) pending.emplace_back(node, next[c]);
                node = next[0];
            }
            build.end_strand(at_line(nodes[from].line));
        }
    }
    // Anything not reached from a root hangs off a parent cycle.
    for (std::uint32_t i = 0; i < nodes.size(); ++i)
        if (!visited[i])
            throw InputError(name + ": line " + std::to_string(nodes[i].line) + ": node " +
                             std::to_string(nodes[i].id) +
                             " is not reachable from any root (its parents form a cycle)");
    return out;
}

}  // namespace rtc
