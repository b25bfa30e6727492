// What the current GL context can do that the methods rely on (probed, not just queried).
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <string>

namespace ss::gl {

struct Capabilities {
    std::string renderer, vendor, version, glsl;
    int maxTextureSize = 0, maxColorAttachments = 0, maxDrawBuffers = 0;
    int maxComputeInvocations = 0;
    bool floatBlending = false;   // RGBA32F additive blending is exact (rendered and read back)
    bool floatFiltering = false;  // linear filtering of an R32F texture interpolates
    bool compute = false;         // a compute shader ran and wrote its result
    // With the device that renders (when the backend has a choice) and every EGL device.
    std::string toJson(const std::string& backend, const std::string& device = "") const;
};

// Must run on the render thread. Probes draw into tiny private targets; GL state is left
// unspecified afterwards (every pass sets its own through render_state.h).
Capabilities probeCapabilities();

}  // namespace ss::gl
