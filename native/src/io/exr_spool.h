// How the passes of many renders are gathered for one multilayer EXR without holding them in
// memory: each pass goes to an unlinked spool file beside the output as it arrives, and the EXR
// is written from it band by band at the end.
// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "core/image.h"

namespace ss {

class ExrSpool {
public:
    // Checks the output path and view layer now (ss::Error naming them) and opens the spool in
    // the output's folder without a name (O_TMPFILE, else unlinked at once): nothing is left
    // behind whatever happens.
    ExrSpool(const std::string& path, const std::string& viewLayer);
    ~ExrSpool();
    ExrSpool(const ExrSpool&) = delete;
    ExrSpool& operator=(const ExrSpool&) = delete;

    // Appends a pass (same size as the first; a unique name whose channel fits EXR's 255 bytes).
    void add(const std::string& pass, const Image& image);
    size_t passCount() const { return passes_.size(); }
    // Records which method made a pass, for the header's kExrMethodsAttribute (io/exr_file.h).
    void noteMethod(const std::string& pass, const std::string& method);
    // Records a pass's estimated RMSE, for the header's kExrEstimatesAttribute.
    void noteEstimate(const std::string& pass, double rmse);
    // Writes the EXR atomically (io/exr_file.h). Throws SS_ERROR_INVALID_ARGUMENT with no pass.
    void write();

private:
    struct Spooled {
        std::string pass;
        uint64_t offset = 0;  // in the spool, in bytes
    };
    std::string path_, viewLayer_;
    int fd_ = -1;
    int width_ = 0, height_ = 0;
    uint64_t end_ = 0;
    std::vector<Spooled> passes_;
    std::set<std::string> names_;
    std::string methods_;    // "<pass>=<method>;..."
    std::string estimates_;  // "<pass>=<rmse>;..."
};

}  // namespace ss
