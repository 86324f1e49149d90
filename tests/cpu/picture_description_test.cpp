// session::resolvePicture's transfer function: presets fitted to the data's percentiles when no
// range is given (spiky and foggy; the others over the range), their range-fixed shape under
// --tf-range or a series' range, files untouched; the same TF from a data-parallel part that holds
// the whole's percentiles (summed counts of the cells each part owns); and a saved session
// renders the same TF without the data being fitted again.
#include "session/picture_description.h"

#include <gtest/gtest.h>

#include <fstream>

#include "amr/space_partition.h"
#include "amr/value_percentiles.h"
#include "model_fixtures.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"
#include "scene/transfer_function.h"
#include "scene/volume.h"
#include "session/session.h"
#include "test_data.h"

using namespace amrvk;
using namespace amrvk::session;

namespace {

scene::TransferFunction resolvedTf(const PictureDescription& d, const scene::Volume& v,
                                   std::vector<std::string>* notes = nullptr) {
    return resolvePicture(d, v, notes).tf.merged();
}

void expectSameTf(const scene::TransferFunction& a, const scene::TransferFunction& b) {
    EXPECT_EQ(a.positions(), b.positions());
    EXPECT_EQ(a.colors(), b.colors());
}

}  // namespace

TEST(PictureDescription, PresetsFollowTheDataUnlessARangeIsGiven) {
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(test::makeThreeLevelCloud());
    const amr::Percentiles& p = v->percentiles;
    ASSERT_LT(p.lo(), p.hi());
    for (const std::string& name : scene::presetNames()) {
        SCOPED_TRACE(name);
        PictureDescription d;
        d.tfSource = TfSource{.name = name};
        std::vector<std::string> notes;
        const scene::TransferFunction fitted = resolvedTf(d, *v, &notes);
        expectSameTf(fitted, scene::makePreset(name, p, v->volumeHistogram));
        EXPECT_EQ(fitted.firstPosition(), v->valueLo());
        EXPECT_EQ(fitted.lastPosition(), v->valueHi());
        if (scene::presetFollowsData(name) && name != "layers") {  // the default says nothing
            ASSERT_EQ(notes.size(), 1u);
            EXPECT_NE(notes[0].find("tf " + name), std::string::npos) << notes[0];
            EXPECT_NE(notes[0].find(name == "spiky" ? "percentiles" : name == "layers" ? "space" : "median"),
                      std::string::npos)
                << notes[0];
        } else {
            EXPECT_TRUE(notes.empty());
        }
        // A series' range: the range-fixed shape over it.
        d.dataRange = std::make_pair(-3.0f, 7.0f);
        expectSameTf(resolvedTf(d, *v), scene::makePreset(name, -3.0f, 7.0f));
        // --tf-range wins over both.
        d.tfRange = std::make_pair(1.0f, 2.0f);
        expectSameTf(resolvedTf(d, *v), scene::makePreset(name, 1.0f, 2.0f));
        d.dataRange.reset();
        expectSameTf(resolvedTf(d, *v), scene::makePreset(name, 1.0f, 2.0f));
    }
    // spiky and foggy: fitted and range-fixed differ (the peaks and the fog sit elsewhere).
    for (const char* name : {"spiky", "foggy"}) {
        PictureDescription d;
        d.tfSource = TfSource{.name = name};
        EXPECT_NE(resolvedTf(d, *v).positions(), scene::makePreset(name, v->valueLo(), v->valueHi()).positions());
    }
}

TEST(PictureDescription, TfFilesKeepTheirPositions) {
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(test::makeThreeLevelCloud());
    const std::filesystem::path file = test::scratchDir() / "tf.json";
    std::ofstream(file) << scene::paraViewPresetJson(scene::TfChannels::split(scene::makePreset("spiky", 10.0f, 20.0f)));
    PictureDescription d;
    d.tfSource = TfSource{.name = file.string()};
    expectSameTf(resolvedTf(d, *v), scene::makePreset("spiky", 10.0f, 20.0f));
}

TEST(PictureDescription, APartInTheWholesFrameGetsTheWholesTfAndCamera) {
    // Data-parallel MPI: each part holds its cells and a halo; counting only the cells it owns and
    // summing the counts over the parts gives the whole's percentiles, so every part fits the same TF.
    amr::Model whole = test::makeThreeLevelCloud();
    const amr::CellCensus census = amr::censusOf(whole);
    const std::vector<amr::Box3l> boxes = amr::partitionByCells(census, 3);
    std::vector<amr::Model> parts;
    std::vector<std::vector<float>> owned(boxes.size());
    for (size_t r = 0; r < boxes.size(); ++r) {
        amr::Model part = whole;
        part.cells.clear();
        part.fields[0].values.clear();
        for (size_t i = 0; i < whole.cells.size(); ++i) {
            if (!amr::supportMeets(whole.cells[i], boxes[r])) continue;
            part.cells.push_back(whole.cells[i]);
            part.fields[0].values.push_back(whole.fields[0].values[i]);
            if (amr::ownsCell(boxes[r], whole.cells[i])) owned[r].push_back(whole.fields[0].values[i]);
        }
        ASSERT_GT(part.cells.size(), owned[r].size());  // a halo
        parts.push_back(std::move(part));
    }
    amr::PercentileSelection s;
    while (!s.done()) {
        std::vector<uint64_t> sum;
        for (const std::vector<float>& o : owned) {
            const std::vector<uint64_t> c = s.count(o);
            sum.resize(c.size(), 0);
            for (size_t i = 0; i < c.size(); ++i) sum[i] += c[i];
        }
        s.advance(sum);
    }
    const std::shared_ptr<const scene::Volume> one = scene::makeVolume(whole);
    PictureDescription d;
    for (const char* name : {"spiky", "foggy"}) {
        d.tfSource = TfSource{.name = name};
        const scene::TransferFunction expected = resolvedTf(d, *one);
        for (amr::Model& part : parts) {
            const scene::VolumeFrame frame{.bounds = census.bounds,
                                           .minLevel = census.minLevel,
                                           .valueLo = census.valueLo,
                                           .valueHi = census.valueHi,
                                           .percentiles = s.result()};
            const std::shared_ptr<const scene::Volume> pv = scene::makeVolume(part, "", frame);
            expectSameTf(resolvedTf(d, *pv), expected);
            // The default camera frames the whole, not the part (a part's own box is smaller).
            PictureDescription fit = d;
            fit.fitCamera = true;
            const scene::Camera full = resolvePicture(fit, *one, nullptr).settings.camera;
            const scene::Camera mine = resolvePicture(fit, *pv, nullptr).settings.camera;
            EXPECT_EQ(mine.eye, full.eye);
            EXPECT_EQ(mine.target, full.target);
            EXPECT_NE(pv->bounds().upper - pv->bounds().lower, one->bounds().upper - one->bounds().lower);
            // Its own cells' percentiles (halo included) would give another TF.
            EXPECT_NE(scene::makePreset(name, amr::percentilesOf(part.fields[0].values)).positions(), expected.positions());
        }
    }
}

TEST(PictureDescription, ASavedSessionKeepsItsFittedTf) {
    // Sessions store the TF's nodes: rendering one again needs no fit and gives the same nodes,
    // whatever data it is shown over.
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(test::makeThreeLevelCloud());
    PictureDescription d;
    d.session.input = "cloud.cells";
    d.tfSource = TfSource{.name = "spiky"};
    const Session fitted = resolvePicture(d, *v, nullptr);
    PictureDescription again;
    again.session = parseSession(sessionJson(fitted), "saved.json");
    expectSameTf(resolvedTf(again, *v), fitted.tf.merged());
    amr::Model other = test::makeThreeLevelCloud();
    for (float& x : other.fields[0].values) x *= 3.0f;
    expectSameTf(resolvedTf(again, *scene::makeVolume(std::move(other))), fitted.tf.merged());
}

// With no field named, the density-like field is shown, and a note says so where it is not the
// first listed (issue 52, point 10: an AMReX plotfile showed x_velocity, its first field).
TEST(PictureDescription, TheDefaultFieldIsSaidWhereItIsNotTheFirst) {
    amr::Model m = test::makeThreeLevelCloud();
    m.fields[0].name = "density";
    m.fields.insert(m.fields.begin(), {"x_velocity", m.fields[0].values});
    m.availableFields = {"x_velocity", "density"};
    const std::shared_ptr<const scene::Volume> v = scene::makeVolume(std::move(m));
    PictureDescription d;
    d.session.input = "plt";
    std::vector<std::string> notes;
    EXPECT_EQ(resolvePicture(d, *v, &notes).field, "density");
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(notes[0],
              "field 'density' shown: the density-like one of 2 (the first listed is 'x_velocity'; "
              "--field NAME shows another)");
    // Named, or the first listed: no note.
    notes.clear();
    d.session.field = "density";
    resolvePicture(d, *v, &notes);
    EXPECT_TRUE(notes.empty());
}
