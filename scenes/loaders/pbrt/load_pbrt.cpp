// The pbrt-v4 scene loader: directives, the transform stack, includes and
// object instances (see loaders.h; the shapes themselves are in shapes.cpp).
// Directive syntax follows pbrt-v4's parser.cpp; transforms are those of
// pbrt-v4's BasicSceneBuilder (the current transform multiplies on the right).
#include "scenes/loaders/file_bytes.h"
#include "scenes/loaders/loaders.h"
#include "scenes/loaders/pbrt/notes.h"
#include "scenes/loaders/pbrt/params.h"
#include "scenes/loaders/pbrt/shapes.h"
#include "scenes/generators/strand_builder.h"
#include "scenes/limits.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace rtc {

namespace {

namespace fs = std::filesystem;
using pbrt::ParamList;
using pbrt::Token;
using pbrt::Tokenizer;

struct Geometry {
    Strands curves;
    TriangleMesh mesh;
    std::size_t curve_shapes = 0, mesh_shapes = 0;
};

struct Saved {
    glm::dmat4 ctm;
    char kind;  // 'a' AttributeBegin, 't' TransformBegin, 'o' ObjectBegin
    std::size_t line;
    std::string file;
};

const char* opener(char kind) {
    return kind == 'a' ? "AttributeBegin" : kind == 't' ? "TransformBegin" : "ObjectBegin";
}

// Directives that take a quoted type or name and a parameter list, checked and skipped.
const std::set<std::string_view> kSkippedWithParams = {
    "Camera", "Sampler", "Film", "Integrator", "PixelFilter", "Accelerator", "LightSource",
    "AreaLightSource", "Material", "MakeNamedMaterial", "MakeNamedMedium", "Attribute"};
const std::set<std::string_view> kSkippedShapes = {"sphere", "disk", "cylinder"};

class Loader {
public:
    Loader(const PbrtLimits& limits, const fs::path& main, CurveBasis basis)
        : limits_(limits), main_file_(main), main_dir_(main.parent_path()), basis_(basis) {}

    void parse_file(const fs::path& file, const Tokenizer* from, std::size_t from_line) {
        auto fail_from = [&](const std::string& problem) {
            if (from) from->fail(from_line, problem);
            throw InputError(file.string() + ": " + problem);
        };
        if (include_stack_.size() >= limits_.max_include_depth)
            fail_from("includes nested deeper than " + std::to_string(limits_.max_include_depth));
        std::error_code ec;
        const fs::path canonical = fs::weakly_canonical(file, ec);
        for (std::size_t i = 0; i < include_stack_.size(); ++i)
            if (include_stack_[i] == canonical) {
                std::string cycle;
                for (std::size_t j = i; j < include_stack_.size(); ++j) cycle += include_stack_[j].string() + " -> ";
                fail_from("include cycle: " + cycle + canonical.string());
            }
        std::vector<std::uint8_t> bytes;
        try {
            bytes = read_file_bytes(file);
        } catch (const InputError& e) {
            if (!from) throw;
            fail_from(std::string("Include: ") + e.what());  // a directory, a device, unreadable
        }
        bytes_ += bytes.size();
        if (bytes_ > limits_.max_bytes)
            fail_from("more than " + std::to_string(limits_.max_bytes) + " bytes read over all included files");
        ++files_;
        include_stack_.push_back(canonical);
        Tokenizer t(std::string(bytes.begin(), bytes.end()), file.string());
        bytes.clear();
        bytes.shrink_to_fit();
        while (std::optional<Token> tok = t.next()) {
            if (!tok->is(Token::Kind::Word)) t.fail(tok->line, "expected a directive, got " + tok->shown());
            directive(t, *tok, file);
        }
        include_stack_.pop_back();
        if (from == nullptr) finish(t);
    }

    PbrtScene take() {
        PbrtScene out;
        out.curves = std::move(world_.curves);
        out.curves.basis = basis_;
        out.mesh = std::move(world_.mesh);
        out.curve_shapes = world_.curve_shapes;
        out.mesh_shapes = world_.mesh_shapes;
        out.files = files_;
        out.skipped_shapes = std::move(skipped_);
        out.camera = camera_;
        out.film_resolution = film_resolution_;
        out.notes = pbrt::scene_notes(out, main_file_);
        return out;
    }

private:
    // Film's x/yresolution for the note, of whatever numeric type the file
    // gave (it was checked when read; the note should not reject a file).
    static double resolution(const ParamList& params, const std::string& name, double fallback) {
        for (const pbrt::Param& p : params.all())
            if (p.name == name && p.numbers.size() == 1) return p.numbers[0];
        return fallback;
    }

    void finish(const Tokenizer& t) {
        if (!stack_.empty())
            throw InputError(stack_.back().file + ": line " + std::to_string(stack_.back().line) + ": " +
                             opener(stack_.back().kind) + " never closed (end of " + t.file() + ")");
    }

    static std::string word_arg(Tokenizer& t, const Token& d, Token::Kind kind) {
        const Token a = t.require(kind == Token::Kind::String ? "a quoted string" : "a word");
        if (!a.is(kind))
            t.fail(a.line, d.shown() + " expects " +
                               (kind == Token::Kind::String ? "a quoted string" : "a bare word") + ", got " + a.shown());
        return std::string(a.text);
    }
    static std::vector<double> numbers(Tokenizer& t, const Token& d, std::size_t n, bool brackets) {
        if (brackets && !t.require("[").is(Token::Kind::Open)) t.fail(t.line(), d.shown() + " expects [ and 16 numbers ]");
        std::vector<double> v;
        for (std::size_t i = 0; i < n; ++i) v.push_back(pbrt::to_number(t, t.require("a number"), d.shown().c_str()));
        if (brackets && !t.require("]").is(Token::Kind::Close)) t.fail(t.line(), d.shown() + " expects exactly 16 numbers in [ ]");
        return v;
    }

    void apply(const glm::dmat4& m) {
        if (transform_start_) ctm_ = ctm_ * m;
    }
    void push(char kind, std::size_t line, const fs::path& file) { stack_.push_back({ctm_, kind, line, file.string()}); }
    void pop(Tokenizer& t, char kind, const Token& d) {
        if (stack_.empty()) t.fail(d.line, d.shown() + " without a matching " + opener(kind));
        if (stack_.back().kind != kind)
            t.fail(d.line, d.shown() + " closes " + opener(stack_.back().kind) + " of " + stack_.back().file +
                               " line " + std::to_string(stack_.back().line));
        ctm_ = stack_.back().ctm;
        stack_.pop_back();
    }

    // Existence without exceptions (a name too long for the file system is "no such file").
    static bool exists(const fs::path& p) {
        std::error_code ec;
        return fs::exists(p, ec);
    }

    fs::path resolve(Tokenizer& t, std::size_t line, const fs::path& including, const std::string& name) {
        const fs::path given(name);
        if (name.empty()) t.fail(line, "empty file name");
        if (given.is_absolute()) {
            if (!exists(given)) t.fail(line, "no such file: " + name);
            return given;
        }
        const fs::path beside = including.parent_path() / given, main = main_dir_ / given;
        if (exists(beside)) return beside;
        if (exists(main)) return main;
        t.fail(line, "no such file: \"" + name + "\" (tried " + beside.string() +
                         (main == beside ? std::string() : " and " + main.string()) + ")");
    }

    void count(Tokenizer& t, std::size_t line, std::uint64_t more) {
        elements_ += more;
        if (elements_ > limits_.max_elements)
            t.fail(line, "the scene grows past " + std::to_string(limits_.max_elements) +
                             " points, vertices and triangles (after instancing)");
    }

    // Appends `g` mapped by `m` (widths scaled by the cube root of its volume scale).
    void append(Tokenizer& t, std::size_t line, Geometry& into, const Geometry& g, const glm::dmat4& m) {
        // The output is bounded; object definitions are bounded by the bytes read.
        if (&into == &world_) count(t, line, g.curves.points.size() + g.mesh.vertices.size() + g.mesh.triangles.size());
        const double width_scale = std::cbrt(std::abs(glm::determinant(glm::dmat3(m))));
        auto map = [&](const Vec3& p) {
            const glm::dvec4 q = m * glm::dvec4(glm::dvec3(p), 1.0);
            for (int i = 0; i < 3; ++i)
                if (!(std::abs(q[i]) <= kMaxCoordinate)) t.fail(line, std::string("a transformed point lies beyond +-") + kMaxCoordinateText);
            return Vec3(glm::dvec3(q));
        };
        const auto base = static_cast<std::uint32_t>(into.curves.points.size());
        for (std::size_t i = 0; i < g.curves.points.size(); ++i) {
            into.curves.points.push_back(map(g.curves.points[i]));
            const double r = g.curves.radii[i] * width_scale;
            if (!(r <= kMaxCoordinate)) t.fail(line, std::string("a transformed width exceeds ") + kMaxCoordinateText);
            into.curves.radii.push_back(static_cast<float>(r));
        }
        for (std::size_t i = 1; i < g.curves.offsets.size(); ++i) into.curves.offsets.push_back(base + g.curves.offsets[i]);
        const auto vbase = static_cast<std::uint32_t>(into.mesh.vertices.size());
        for (const Vec3& v : g.mesh.vertices) into.mesh.vertices.push_back(map(v));
        for (const auto& tri : g.mesh.triangles) into.mesh.triangles.push_back({vbase + tri[0], vbase + tri[1], vbase + tri[2]});
        into.curve_shapes += g.curve_shapes;
        into.mesh_shapes += g.mesh_shapes;
    }

    void shape(Tokenizer& t, const Token& d, const fs::path& file) {
        const std::string type = word_arg(t, d, Token::Kind::String);
        const std::size_t line = t.line();
        const ParamList params = ParamList::read(t);
        Geometry g;
        if (type == "curve") {
            pbrt::add_curve(params, g.curves, basis_);
            g.curve_shapes = 1;
        } else if (type == "trianglemesh" || type == "loopsubdiv") {
            pbrt::add_triangle_mesh(params, g.mesh);
            g.mesh_shapes = 1;
        } else if (type == "bilinearmesh") {
            pbrt::add_bilinear_mesh(params, g.mesh);
            g.mesh_shapes = 1;
        } else if (type == "plymesh") {
            const std::string name = params.string("filename", "");
            if (name.empty()) t.fail(line, "plymesh needs \"string filename\"");
            const fs::path ply = resolve(t, line, file, name);
            if (ply.extension() == ".gz") t.fail(line, "plymesh \"" + name + "\": compressed PLY is not supported (gunzip it)");
            try {
                g.mesh = load_assimp_mesh(ply, limits_.max_bytes);
            } catch (const InputError& e) {
                t.fail(line, std::string("plymesh: ") + e.what());
            }
            g.mesh_shapes = 1;
        } else if (kSkippedShapes.count(type)) {
            ++skipped_[type];
            return;
        } else {
            t.fail(line, "unknown shape \"" + type + "\"");
        }
        append(t, line, object_ ? object_->second : world_, g, ctm_);
    }

    void directive(Tokenizer& t, const Token& d, const fs::path& file) {
        const std::string_view name = d.text;
        if (name == "Shape") return shape(t, d, file);
        if (kSkippedWithParams.count(name)) {
            const std::string type = word_arg(t, d, Token::Kind::String);
            // pbrt-v4: the coordinate system "camera" is world-from-camera.
            if (name == "Camera" && glm::determinant(ctm_) != 0.0) named_["camera"] = glm::inverse(ctm_);
            if (name == "Camera") camera_ = type;
            const ParamList params = ParamList::read(t);
            if (name == "Film") film_resolution_ = {resolution(params, "xresolution", 1280),  // pbrt-v4's defaults
                                                    resolution(params, "yresolution", 720)};
            return;
        }
        if (name == "Texture") {
            for (int i = 0; i < 3; ++i) (void)word_arg(t, d, Token::Kind::String);
            (void)ParamList::read(t);
        } else if (name == "Option") {
            if (ParamList::read(t).all().size() != 1) t.fail(d.line, "Option expects one parameter");
        } else if (name == "Include" || name == "Import") {
            const std::string inc = word_arg(t, d, Token::Kind::String);
            parse_file(resolve(t, t.line(), file, inc), &t, t.line());
        } else if (name == "Translate" || name == "Scale") {
            const auto v = numbers(t, d, 3, false);
            const glm::dvec3 x(v[0], v[1], v[2]);
            apply(name == "Translate" ? glm::translate(glm::dmat4(1.0), x) : glm::scale(glm::dmat4(1.0), x));
        } else if (name == "Rotate") {
            const auto v = numbers(t, d, 4, false);
            const glm::dvec3 axis(v[1], v[2], v[3]);
            if (!(glm::length(axis) > 0.0)) t.fail(d.line, "Rotate about a zero axis");
            apply(glm::rotate(glm::dmat4(1.0), glm::radians(v[0]), glm::normalize(axis)));
        } else if (name == "LookAt") {
            apply(look_at(t, d, numbers(t, d, 9, false)));
        } else if (name == "Transform" || name == "ConcatTransform") {
            const auto v = numbers(t, d, 16, true);
            glm::dmat4 m;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) m[c][r] = v[static_cast<std::size_t>(4 * c + r)];  // pbrt: column-major
            if (name == "Transform") {
                if (transform_start_) ctm_ = m;
            } else {
                apply(m);
            }
        } else if (name == "Identity") {
            if (transform_start_) ctm_ = glm::dmat4(1.0);
        } else if (name == "CoordinateSystem") {
            named_[word_arg(t, d, Token::Kind::String)] = ctm_;
        } else if (name == "CoordSysTransform") {
            const std::string n = word_arg(t, d, Token::Kind::String);
            const auto it = named_.find(n);
            if (it == named_.end()) t.fail(d.line, "no coordinate system named \"" + n + "\"");
            if (transform_start_) ctm_ = it->second;
        } else if (name == "ActiveTransform") {
            const std::string which = word_arg(t, d, Token::Kind::Word);
            if (which != "StartTime" && which != "EndTime" && which != "All")
                t.fail(d.line, "ActiveTransform expects StartTime, EndTime or All, got " + which);
            transform_start_ = which != "EndTime";  // the loader keeps the start-time transform
        } else if (name == "TransformTimes") {
            (void)numbers(t, d, 2, false);
        } else if (name == "AttributeBegin" || name == "TransformBegin") {
            push(name == "AttributeBegin" ? 'a' : 't', d.line, file);
        } else if (name == "AttributeEnd" || name == "TransformEnd") {
            pop(t, name == "AttributeEnd" ? 'a' : 't', d);
        } else if (name == "ObjectBegin") {
            const std::string n = word_arg(t, d, Token::Kind::String);
            if (object_) t.fail(d.line, "ObjectBegin \"" + n + "\" inside ObjectBegin \"" + object_->first + "\"");
            if (objects_.count(n)) t.fail(d.line, "object \"" + n + "\" defined twice");
            push('o', d.line, file);
            object_.emplace(n, Geometry{});
        } else if (name == "ObjectEnd") {
            pop(t, 'o', d);
            if (!object_) t.fail(d.line, "ObjectEnd outside an object");
            objects_.emplace(object_->first, std::move(object_->second));
            object_.reset();
        } else if (name == "ObjectInstance") {
            const std::string n = word_arg(t, d, Token::Kind::String);
            if (object_) t.fail(d.line, "ObjectInstance inside ObjectBegin \"" + object_->first + "\"");
            const auto it = objects_.find(n);
            if (it == objects_.end()) t.fail(d.line, "no object named \"" + n + "\"");
            append(t, d.line, world_, it->second, ctm_);
        } else if (name == "WorldBegin") {
            ctm_ = glm::dmat4(1.0);
            named_["world"] = ctm_;
        } else if (name == "NamedMaterial" || name == "ColorSpace") {
            (void)word_arg(t, d, Token::Kind::String);
        } else if (name == "MediumInterface") {
            (void)word_arg(t, d, Token::Kind::String);
            if (t.peek() && t.peek()->is(Token::Kind::String)) (void)t.next();
        } else if (name != "ReverseOrientation" && name != "WorldEnd") {
            t.fail(d.line, "unknown directive " + d.shown());
        }
    }

    // pbrt-v4 LookAt: camera-from-world for an eye at `pos` looking at `look`.
    static glm::dmat4 look_at(Tokenizer& t, const Token& d, const std::vector<double>& v) {
        const glm::dvec3 pos(v[0], v[1], v[2]), look(v[3], v[4], v[5]), up(v[6], v[7], v[8]);
        if (!(glm::length(look - pos) > 0.0) || !(glm::length(up) > 0.0))
            t.fail(d.line, "LookAt with the eye on the target or a zero up vector");
        const glm::dvec3 dir = glm::normalize(look - pos);
        const glm::dvec3 right = glm::cross(glm::normalize(up), dir);
        if (!(glm::length(right) > 0.0)) t.fail(d.line, "LookAt: up vector and viewing direction are parallel");
        const glm::dvec3 r = glm::normalize(right), new_up = glm::cross(dir, r);
        const glm::dmat4 world_from_camera(glm::dvec4(r, 0), glm::dvec4(new_up, 0), glm::dvec4(dir, 0), glm::dvec4(pos, 1));
        return glm::inverse(world_from_camera);
    }

    const PbrtLimits& limits_;
    fs::path main_file_, main_dir_;
    CurveBasis basis_;
    glm::dmat4 ctm_{1.0};
    bool transform_start_ = true;
    std::vector<Saved> stack_;
    std::map<std::string, glm::dmat4> named_;
    std::map<std::string, Geometry> objects_;
    std::optional<std::pair<std::string, Geometry>> object_;
    std::vector<fs::path> include_stack_;
    Geometry world_;
    std::map<std::string, std::size_t> skipped_;
    std::string camera_;
    std::array<double, 2> film_resolution_{0.0, 0.0};
    std::uint64_t bytes_ = 0, elements_ = 0;
    std::size_t files_ = 0;
};

}  // namespace

PbrtScene load_pbrt(const std::filesystem::path& file, const PbrtLimits& limits, CurveBasis basis) {
    Loader loader(limits, file, basis);
    loader.parse_file(file, nullptr, 0);
    return loader.take();
}

}  // namespace rtc
