// Picking a curve loader by name or by file extension.
#include "scenes/loaders/loaders.h"

#include "core/input_error.h"

#include <algorithm>
#include <cctype>

namespace rtc {

std::optional<CurveFormat> curve_format_from_name(std::string_view name) {
    if (name == "auto") return CurveFormat::Auto;
    if (name == "hair") return CurveFormat::Hair;
    if (name == "tfx") return CurveFormat::Tfx;
    if (name == "trk") return CurveFormat::Trk;
    if (name == "swc") return CurveFormat::Swc;
    if (name == "obj") return CurveFormat::Obj;
    if (name == "txt") return CurveFormat::Txt;
    if (name == "pbrt") return CurveFormat::Pbrt;
    return std::nullopt;
}

CurveFormat resolve_curve_format(const std::filesystem::path& file, CurveFormat format) {
    if (format != CurveFormat::Auto) return format;
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const auto f = ext.empty() ? std::nullopt : curve_format_from_name(ext.substr(1));
    if (!f || *f == CurveFormat::Auto)
        throw InputError(file.string() + ": cannot tell the curve format from the extension \"" +
                         ext + "\" (use .hair .tfx .trk .swc .obj .txt .pbrt or name the format)");
    return *f;
}

CurveBasis default_curve_basis(CurveFormat resolved) {
    return resolved == CurveFormat::Pbrt ? CurveBasis::Bezier : CurveBasis::BSpline;
}

namespace {

LoadedCurves read_curves(const std::filesystem::path& file, CurveFormat format, CurveBasis basis) {
    switch (format) {
        case CurveFormat::Hair: return load_hair(file);
        case CurveFormat::Tfx: return load_tfx(file);
        case CurveFormat::Trk: return load_trk(file);
        case CurveFormat::Swc: return load_swc(file);
        case CurveFormat::Txt: return load_txt(file);
        case CurveFormat::Obj: {
            ObjContents obj = load_obj(file);
            if (obj.lines.strand_count() == 0)
                throw InputError(file.string() + ": no `l` polylines in this OBJ file");
            return {std::move(obj.lines), false, {}};
        }
        case CurveFormat::Pbrt: {
            PbrtScene pbrt = load_pbrt(file, {}, basis);
            if (pbrt.curves.strand_count() == 0)
                throw InputError(file.string() + ": no `Shape \"curve\"` in this pbrt file");
            return {std::move(pbrt.curves), true, std::move(pbrt.notes)};
        }
        case CurveFormat::Auto: break;
    }
    throw InputError(file.string() + ": unknown curve format");
}

}  // namespace

LoadedCurves load_curves(const std::filesystem::path& file, CurveFormat format, std::optional<CurveBasis> basis) {
    format = resolve_curve_format(file, format);
    const CurveBasis b = basis.value_or(default_curve_basis(format));
    LoadedCurves out = read_curves(file, format, b);
    out.strands.basis = b;
    return out;
}

}  // namespace rtc
