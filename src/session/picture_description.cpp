#include "session/picture_description.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/progress.h"
#include "core/strings.h"
#include "scene/camera.h"
#include "scene/command_line.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"

namespace amrvk::session {

std::shared_ptr<const scene::Volume> loadVolume(const Session& s, const scene::VolumeOptions& options) {
    AMRVK_CHECK(!s.input.empty(), "no input data set (give one, or --session FILE)");
    amr::ReadOptions ro = s.read;
    if (!s.field.empty()) ro.fields = {s.field};
    amr::Model model;
    {
        ProgressStage stage("reading " + s.input);
        model = amr::readModel(s.input, ro);
    }
    return scene::makeVolume(std::move(model), s.field, options);
}

namespace {
// What a fitted preset was laid over, one line (`series`: a series' pooled or first percentiles).
std::string fittedPresetNote(const std::string& name, const amr::Percentiles& p, const scene::TransferFunction& tf,
                             bool series) {
    auto formatNumber = [](float v) {
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", double(v));
        return std::string(text);
    };
    if (!(p.lo() < p.hi())) return strCat("tf ", name, ": the field has one value (", formatNumber(p.lo()), ")");
    if (name == "spiky")
        return strCat("tf spiky: alpha-1 peaks at the 75th, 90th and 97th percentiles of the ",
                      series ? "series' " : "", "cell values (", formatNumber(p[75]), ", ", formatNumber(p[90]), ", ",
                      formatNumber(p[97]), ")");
    return strCat("tf foggy: alpha 0 up to the median ", series ? "of the series' cell values" : "cell value", " (",
                  formatNumber(p[50]), "), ", formatNumber(tf.maxAlpha(p.lo(), p.hi())), " at the maximum (",
                  formatNumber(p.hi()), ")");
}
}  // namespace

Session resolvePicture(const PictureDescription& d, const scene::Volume& v, std::vector<std::string>* notes) {
    Session s = d.session;
    s.field = v.field().name;
    // The density-like default (amr::defaultFieldIndex) said where it is not the first field listed.
    const std::vector<std::string>& listed = v.model.availableFields;
    if (d.session.field.empty() && notes && !listed.empty() && listed.front() != s.field)
        notes->push_back(strCat("field '", s.field, "' shown: the density-like one of ", listed.size(),
                                " (the first listed is '", listed.front(), "'; --field NAME shows another)"));
    if (s.read.scale == amr::FieldScale::Auto) s.read.scale = amr::scaleOf(v.model);  // as the field decided
    if (d.tfSource || d.tfRange) {
        // A series' distribution stands for the volume's own.
        const amr::Percentiles& data = d.dataPercentiles ? *d.dataPercentiles : v.percentiles;
        const amr::VolumeHistogram noHistogram;
        const amr::VolumeHistogram& volumes = !d.dataPercentiles ? v.volumeHistogram
                                              : d.dataHistogram  ? *d.dataHistogram
                                                                 : noHistogram;
        const std::pair<float, float> range = d.tfRange           ? *d.tfRange
                                              : d.dataRange       ? *d.dataRange
                                              : d.dataPercentiles ? std::make_pair(data.lo(), data.hi())
                                                                  : std::make_pair(v.valueLo(), v.valueHi());
        const float lo = range.first, hi = range.second;
        AMRVK_CHECK(!d.tfRange || (std::isfinite(lo) && std::isfinite(hi)), "--tf-range ", lo, " ", hi,
                    ": LO and HI must be finite");
        AMRVK_CHECK(!d.tfRange || lo < hi, "--tf-range ", lo, " ", hi, ": LO must be below HI");
        // No range given: presets follow the data's distribution; a given range fixes them.
        const bool fitted = !d.tfRange && !d.dataRange;
        scene::TransferFunction tf =
            !d.tfSource ? s.tf.merged()
            : fitted    ? scene::loadTransferFunction(d.tfSource->name, data, volumes, d.tfSource->preset)
                        : scene::loadTransferFunction(d.tfSource->name, lo, hi, d.tfSource->preset);
        if (d.tfRange) tf = tf.rescaled(lo, hi);
        // spiky and foggy say where they were laid; the default (layers) adds no line to every picture.
        if (fitted && d.tfSource && scene::presetFollowsData(d.tfSource->name) && d.tfSource->name != "layers" && notes)
            notes->push_back(fittedPresetNote(d.tfSource->name, data, tf, d.dataPercentiles.has_value()));
        s.tf = scene::TfChannels::split(tf);
    }
    if (d.fitCamera)  // the whole data set, also where v is one MPI rank's part of it
        s.settings.camera = scene::defaultCamera(v.frameWorldLo(), v.frameWorldHi(), s.settings.camera.fovYDegrees);
    if (d.fit == StructureFit::Data && s.structure.sampler != scene::SamplerKind::Dense) {
        std::string why;
        s.structure.traversal = scene::fittingTraversal(v.summary.leafVolume, v.bounds().volume(), &why);
        // Over sparse data the grid sampler's macrocells would list many far-apart bricks; with the
        // abr traversal the abr sampler needs no lookup at all.
        if (!d.isGiven("sampler") && s.structure.traversal == scene::TraversalKind::Abr) {
            s.structure.sampler = scene::SamplerKind::Abr;
            if (why.rfind("traversal abr", 0) == 0) why.insert(13, " and sampler abr");
        }
        if (!why.empty() && notes) notes->push_back(why);
    }
    if (d.fit != StructureFit::Probe) s.structure.validate();
    return s;
}

std::string renderCommandLine(const PictureDescription& d, const std::string& tfFile, const std::string& output,
                              const std::string& renderer) {
    using scene::formatNumber;
    using scene::shellQuote;
    const Session& s = d.session;
    std::string c = shellQuote(renderer) + " render " + shellQuote(s.input);
    if (!s.field.empty()) c += " --field " + shellQuote(s.field);
    if (s.read.format != "auto") c += " --format " + shellQuote(s.read.format);
    if (s.read.nanPolicy == amr::NanPolicy::Drop) c += " --nan drop";
    if (s.read.scale != amr::FieldScale::Auto) c += std::string(" --scale ") + amr::fieldScaleName(s.read.scale);
    if (s.read.logFloor != 0.0) c += " --log-floor " + formatNumber(s.read.logFloor);
    if (s.read.rawDims != glm::ivec3(0))
        c += " --dims " + std::to_string(s.read.rawDims.x) + " " + std::to_string(s.read.rawDims.y) + " " +
             std::to_string(s.read.rawDims.z);
    if (!s.read.rawType.empty()) c += " --type " + shellQuote(s.read.rawType);
    if (s.read.rawThreshold != 0.0) c += " --threshold " + formatNumber(s.read.rawThreshold);
    if (d.tfSource) {
        c += " --tf " + shellQuote(d.tfSource->name);
        if (!d.tfSource->preset.empty()) c += " --tf-preset " + shellQuote(d.tfSource->preset);
    } else {
        c += " --tf " + shellQuote(tfFile);
    }
    if (d.tfRange) c += " --tf-range " + formatNumber(d.tfRange->first) + " " + formatNumber(d.tfRange->second);
    c += std::string(" --tf-colors ") + scene::tfColorsName(s.tfColors);  // always: a bench cache key says it
    c += scene::settingsOptions(s.settings, !d.fitCamera);
    c += " --spp " + std::to_string(s.spp > 0 ? s.spp : 64);
    c += scene::structureOptions(s.structure);
    if (s.legend.show) {
        c += " --legend";
        if (s.legend.place != LegendPlace::Side) c += std::string(" --legend-place ") + legendPlaceName(s.legend.place);
    }
    if (!s.legend.title.empty()) c += " --legend-title " + shellQuote(s.legend.title);
    if (!s.legend.units.empty()) c += " --legend-units " + shellQuote(s.legend.units);
    if (!s.legend.font.empty()) c += " --legend-font " + shellQuote(s.legend.font);
    c += " -o " + shellQuote(output);
    return c;
}

std::string renderCommandLine(const Session& s, const std::string& tfFile, const std::string& output) {
    PictureDescription d;
    d.session = s;
    return renderCommandLine(d, tfFile, output);
}

}  // namespace amrvk::session
