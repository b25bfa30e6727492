// Whether passes are written to EXR with the exact channel names Blender lists, as float32,
// read back bit-exactly, written atomically, and whether PNG previews quantise as documented.
// SPDX-License-Identifier: GPL-3.0-or-later
#include <unistd.h>

#include <filesystem>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/exr_file.h"
#include "io/pass_names.h"
#include "io/png_preview.h"

namespace ss {
namespace {

namespace fs = std::filesystem;

fs::path tempDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("ss_io_exr_" + std::to_string(getpid()) + "_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

size_t entries(const fs::path& dir) {
    return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}));
}

Image ramp(int w, int h, float offset) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.at(x, y) = offset + 0.001f * float(y * w + x);
    return img;
}

TEST(IoPassNames, FollowTheDesignContract) {
    EXPECT_EQ(passName("Area", "reference", "V"), "Area_reference");
    EXPECT_EQ(passName("Area.001 key", "shadow_map", "mask"), "Area_001_key_shadow_map_mask");
    EXPECT_EQ(channelName("ViewLayer", "Area_reference"), "ViewLayer.Area_reference.V");
    EXPECT_EQ(channelName("View Layer", "A_pcss_umbra"), "View Layer.A_pcss_umbra.V");
}

TEST(IoPassNames, SplitFindsTheMethod) {
    PassParts p;
    ASSERT_TRUE(splitPassName("Area_001_key_shadow_map_mask", &p));
    EXPECT_EQ(p.light, "Area_001_key");
    EXPECT_EQ(p.method, "shadow_map");
    EXPECT_EQ(p.layer, "mask");
    ASSERT_TRUE(splitPassName("Sun_penumbra_map", &p));
    EXPECT_EQ(p.light, "Sun");
    EXPECT_EQ(p.method, "penumbra_map");
    EXPECT_EQ(p.layer, "V");
    ASSERT_TRUE(splitPassName("my_reference_light_reference_umbra", &p));
    EXPECT_EQ(p.light, "my_reference_light");
    EXPECT_EQ(p.layer, "umbra");
    ASSERT_TRUE(splitPassName("Key_auto_mask", &p));  // a light rendered with auto keeps this name
    EXPECT_EQ(p.light, "Key");
    EXPECT_EQ(p.method, "auto");
    EXPECT_EQ(p.layer, "mask");
    ASSERT_TRUE(splitPassName("Key_auto_pcss", &p));  // a light named "Key auto" with pcss
    EXPECT_EQ(p.light, "Key_auto");
    EXPECT_EQ(p.method, "pcss");
    EXPECT_FALSE(splitPassName("Combined", &p));
}

TEST(IoExr, RoundTripWithExactChannelNames) {
    fs::path dir = tempDir("roundtrip");
    std::string path = (dir / "out.exr").string();
    Image v = ramp(13, 7, 0.0f), mask = ramp(13, 7, 0.5f);
    v.at(0, 0) = 0.123456789f;  // the top-left pixel stays at row 0
    writeMultilayerExr(path, "ViewLayer",
                       {{passName("Key.001", "reference", "V"), &v}, {passName("Key.001", "reference", "mask"), &mask}});
    EXPECT_EQ(entries(dir), 1u);  // no temporary left

    // The raw channel names and pixel type, as Blender and any EXR reader see them.
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<std::string> names(spec.channelnames.begin(), spec.channelnames.end());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"ViewLayer.Key_001_reference.V", "ViewLayer.Key_001_reference_mask.V"}));
    for (int c = 0; c < spec.nchannels; ++c) EXPECT_EQ(spec.channelformat(c), OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(spec.width, 13);
    EXPECT_EQ(spec.height, 7);
    in->close();

    ExrContents back = readMultilayerExr(path);
    const ExrPass* pv = back.find("Key_001_reference");
    const ExrPass* pm = back.find("Key_001_reference_mask");
    ASSERT_TRUE(pv && pm);
    EXPECT_EQ(pv->layer, "ViewLayer");
    EXPECT_EQ(pv->channel, "V");
    EXPECT_EQ(pv->image.pixels, v.pixels);  // float32, bit-exact, same row order
    EXPECT_EQ(pm->image.pixels, mask.pixels);
    fs::remove_all(dir);
}

TEST(IoExr, OverwritesAnExistingFile) {
    fs::path dir = tempDir("overwrite");
    std::string path = (dir / "out.exr").string();
    Image a(4, 4, 0.25f), b(4, 4, 0.75f);
    writeMultilayerExr(path, "ViewLayer", {{"L_reference", &a}});
    writeMultilayerExr(path, "ViewLayer", {{"L_shadow_map", &b}});
    ExrContents back = readMultilayerExr(path);
    ASSERT_EQ(back.passes.size(), 1u);
    EXPECT_EQ(back.passes[0].pass, "L_shadow_map");
    EXPECT_EQ(entries(dir), 1u);
    fs::remove_all(dir);
}

TEST(IoExr, UnwritablePathLeavesNothing) {
    fs::path dir = tempDir("unwritable");
    Image a(4, 4, 0.5f);
    // A folder that does not exist, and a path that is a folder (root ignores permissions, so
    // these are the unwritable paths a test can rely on).
    for (std::string path : {(dir / "missing" / "out.exr").string(), dir.string()}) {
        try {
            writeMultilayerExr(path, "ViewLayer", {{"L_reference", &a}});
            FAIL() << "expected an error for " << path;
        } catch (const Error& e) {
            EXPECT_EQ(e.status(), SS_ERROR_IO);
            EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(entries(dir), 0u);
    fs::remove_all(dir);
}

TEST(IoExr, RejectsBadPasses) {
    Image a(4, 4), b(5, 4);
    EXPECT_THROW(writeMultilayerExr("/tmp/x.exr", "ViewLayer", {}), Error);
    EXPECT_THROW(writeMultilayerExr("/tmp/x.exr", "ViewLayer", {{"A_reference", &a}, {"A_reference", &a}}), Error);
    EXPECT_THROW(writeMultilayerExr("/tmp/x.exr", "ViewLayer", {{"A_reference", &a}, {"B_reference", &b}}), Error);
    EXPECT_THROW(writeMultilayerExr("/tmp/x.exr", "ViewLayer", {{"A.reference", &a}}), Error);
}

TEST(IoExr, ReadingAMissingFileNamesIt) {
    try {
        readMultilayerExr("/nonexistent/in.exr");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), SS_ERROR_IO);
        EXPECT_NE(std::string(e.what()).find("/nonexistent/in.exr"), std::string::npos);
    }
}

TEST(IoPng, QuantisesVisibilityTo8Bits) {
    fs::path dir = tempDir("png");
    std::string path = (dir / "p.png").string();
    Image img(4, 1);
    img.pixels = {0.0f, 0.5f, 1.0f, 2.0f};  // 0.5 * 255 = 127.5 rounds to 128; 2 clamps to 255
    writePngPreview(path, img);
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().nchannels, 1);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
    unsigned char px[4];
    ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, px));
    EXPECT_EQ(px[0], 0);
    EXPECT_EQ(px[1], 128);
    EXPECT_EQ(px[2], 255);
    EXPECT_EQ(px[3], 255);
    in->close();
    EXPECT_EQ(entries(dir), 1u);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace ss
