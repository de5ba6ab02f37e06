// An uploaded file (a mesh, a fit target) read by a reader that takes paths: the body's bytes are checked
// (a raw file type, not empty, within config.max_upload_bytes) and stored in a private temporary file for
// the reader, and the reader's messages name the upload instead of that file.
#pragma once
#include "http_policy.h"
#include "private_temp_dir.h"

#include <functional>
#include <string>

namespace iarap::serve {

// Throws HttpError 415 / 400 / 413 for the body (what: "mesh file", "target file"), and what read throws,
// InputError messages rewritten to name `name`.
void read_uploaded_file(const httplib::Request& req, const std::string& name, const std::string& ext,
                        const char* what, const ServeConfig& config, PrivateTempDir& temp,
                        const std::function<void(const std::string& path)>& read);

} // namespace iarap::serve
