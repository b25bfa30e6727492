// How the C API writes render results as one multilayer EXR (at once, or gathered result by
// result, with staged PNG previews), checks outputs before a render, names passes and compares
// visibility EXRs.
// SPDX-License-Identifier: GPL-3.0-or-later
#include "capi/capi_internal.h"
#include "core/names.h"
#include "io/exr_compare.h"
#include "io/exr_file.h"
#include "io/exr_spool.h"
#include "io/pass_names.h"
#include "io/png_preview.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <vector>

#include "io/atomic_file.h"

using namespace ss::capi;

struct ss_exr_writer {
    ss_exr_writer(const std::string& path, const std::string& viewLayer) : spool(path, viewLayer) {}
    ss::ExrSpool spool;
    std::string previewFolder;               // empty: no previews
    std::vector<ss::StagedFile> previews;    // renamed into place after the EXR
    std::set<std::string> previewFiles;      // their file names, which must differ
    bool finished = false;
};

namespace {

// Stages the PNG preview of one pass in the writer's preview folder.
void stagePreview(ss_exr_writer& writer, const std::string& pass, const ss::Image& image) {
    std::string file = ss::previewFileName(pass);
    if (!writer.previewFiles.insert(file).second)
        ss::fail(SS_ERROR_INVALID_ARGUMENT, "two passes would share the preview '" + file + "' in '" +
                                                writer.previewFolder +
                                                "' (light names that differ only in '/', '.' or control characters)");
    std::string path = (std::filesystem::path(writer.previewFolder) / file).string();
    writer.previews.push_back(ss::stagePngPreview(path, image));
}

}  // namespace

extern "C" {

SS_API ss_status ss_write_exr(const char* path, const char* view_layer,
                              const ss_result* const* results, int32_t result_count) {
    return guarded([&] {
        require(path, "ss_write_exr", "path");
        if (result_count <= 0)
            ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_write_exr: there are no results to write to '" +
                                                    std::string(path) + "'");
        require(results, "ss_write_exr", "results");
        std::string layer = view_layer ? view_layer : "ViewLayer";
        ss::checkViewLayerName(layer);
        std::vector<ss::ExrPassRef> passes;
        std::string methods;    // "<pass>=<method that ran>;..."
        std::string estimates;  // "<pass>=<estimated rmse>;..."
        for (int32_t i = 0; i < result_count; ++i) {
            const ss_result* r = results[i];
            if (!r)
                ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_write_exr: results[" + std::to_string(i) + "] is null");
            for (const auto& [name, image] : r->layers.items)
                passes.push_back({ss::passName(r->light, r->requested, name), &image});
            methods += (methods.empty() ? "" : ";") + ss::passName(r->light, r->requested, "V") + "=" + r->method;
            if (std::isfinite(r->estimatedRmse))
                estimates += (estimates.empty() ? "" : ";") + ss::passName(r->light, r->requested, "V") + "=" +
                             ss::formatEstimate(r->estimatedRmse);
        }
        ss::writeMultilayerExr(path, layer, passes, methods, estimates);
    });
}

SS_API ss_status ss_exr_writer_create(const char* path, const char* view_layer, ss_exr_writer** out) {
    return guarded([&] {
        require(out, "ss_exr_writer_create", "out");
        *out = nullptr;
        require(path, "ss_exr_writer_create", "path");
        *out = new ss_exr_writer(path, view_layer ? view_layer : "ViewLayer");
    });
}

SS_API ss_status ss_exr_writer_add(ss_exr_writer* writer, const ss_result* result) {
    return guarded([&] {
        require(writer, "ss_exr_writer_add", "writer");
        require(result, "ss_exr_writer_add", "result");
        if (writer->finished) ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_exr_writer_add: the writer has finished");
        for (const auto& [name, image] : result->layers.items)
            writer->spool.add(ss::passName(result->light, result->requested, name), image);
        if (!writer->previewFolder.empty())
            for (const auto& [name, image] : result->layers.items)
                stagePreview(*writer, ss::passName(result->light, result->method, name), image);
        writer->spool.noteMethod(ss::passName(result->light, result->requested, "V"), result->method);
        if (std::isfinite(result->estimatedRmse))
            writer->spool.noteEstimate(ss::passName(result->light, result->requested, "V"), result->estimatedRmse);
    });
}

SS_API ss_status ss_exr_writer_finish(ss_exr_writer* writer) {
    return guarded([&] {
        require(writer, "ss_exr_writer_finish", "writer");
        if (writer->finished) ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_exr_writer_finish: called twice");
        writer->spool.write();
        for (ss::StagedFile& preview : writer->previews) preview.commit();
        writer->finished = true;
    });
}

SS_API ss_status ss_exr_writer_set_preview_folder(ss_exr_writer* writer, const char* folder) {
    return guarded([&] {
        require(writer, "ss_exr_writer_set_preview_folder", "writer");
        require(folder, "ss_exr_writer_set_preview_folder", "folder");
        if (!*folder) ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_exr_writer_set_preview_folder: folder is empty");
        writer->previewFolder = folder;
    });
}

SS_API ss_status ss_check_exr_shape(const char* path, int64_t pass_count, int32_t width) {
    return guarded([&] {
        require(path, "ss_check_exr_shape", "path");
        if (pass_count < 0 || width < 0)
            ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_check_exr_shape: negative pass count or width");
        ss::checkExrShape(path, size_t(pass_count), width);
    });
}

SS_API ss_status ss_check_output_path(const char* path) {
    return guarded([&] {
        require(path, "ss_check_output_path", "path");
        std::filesystem::path target(ss::resolveOutputPath(path));
        std::filesystem::path dir = target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
        if (access(dir.c_str(), W_OK) != 0)
            ss::fail(SS_ERROR_IO, "cannot write '" + std::string(path) + "': folder '" + dir.string() +
                                      "' is not writable (" + std::strerror(errno) + ")");
    });
}

SS_API void ss_exr_writer_destroy(ss_exr_writer* writer) {
    guarded([&] { delete writer; });
}

SS_API ss_status ss_pass_name(const char* light, const char* method, const char* layer, char* buffer,
                              size_t buffer_size) {
    return guarded([&] {
        require(light, "ss_pass_name", "light");
        require(method, "ss_pass_name", "method");
        copyOut(ss::passName(light, method, layer ? layer : "V"), buffer, buffer_size, "ss_pass_name");
    });
}

SS_API ss_status ss_write_png_preview(const char* path, const float* pixels, int32_t width, int32_t height) {
    return guarded([&] {
        require(path, "ss_write_png_preview", "path");
        require(pixels, "ss_write_png_preview", "pixels");
        if (width <= 0 || height <= 0)
            ss::fail(SS_ERROR_INVALID_ARGUMENT, "ss_write_png_preview: " + std::to_string(width) + "x" +
                                                    std::to_string(height) + " is not an image size");
        ss::Image image(width, height);
        image.pixels.assign(pixels, pixels + size_t(width) * size_t(height));
        ss::writePngPreview(path, image);
    });
}

SS_API ss_status ss_compare_exr(const char* path_a, const char* path_b, const char* against, const char* mask,
                                char* buffer, size_t buffer_size, size_t* length) {
    return guarded([&] {
        require(path_a, "ss_compare_exr", "path_a");
        std::string json = ss::compareExrFiles(path_a, path_b ? path_b : "", against && *against ? against : "reference",
                                               mask ? mask : "");
        if (length) *length = json.size() + 1;
        copyOut(json, buffer, buffer_size, "ss_compare_exr");
    });
}

}  // extern "C"
