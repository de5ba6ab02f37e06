#include "uploaded_file.h"

#include "http_error.h"

#include "iarap/core/errors.h"

#include <fstream>

namespace iarap::serve {
namespace {

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); !from.empty() && at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

} // namespace

void read_uploaded_file(const httplib::Request& req, const std::string& name, const std::string& ext,
                        const char* what, const ServeConfig& config, PrivateTempDir& temp,
                        const std::function<void(const std::string& path)>& read) {
  require_raw_file(req);
  if (req.body.empty())
    throw HttpError(400, std::string("upload body is empty; send the ") + what + "'s bytes");
  if (req.body.size() > config.max_upload_bytes)
    throw HttpError(413, "upload has " + std::to_string(req.body.size()) +
                             " bytes; the limit for file uploads is " +
                             byte_limit_text(config.max_upload_bytes));
  ScopedFile file(temp.unique_path("upload", ext));
  {
    std::ofstream out(file.path(), std::ios::binary);
    out.write(req.body.data(), static_cast<std::streamsize>(req.body.size()));
    if (!out) throw Error("cannot store the upload in the server's temporary folder");
  }
  try {
    read(file.path().string());
  } catch (const InputError& e) { // name the upload, not the server's temporary path
    throw InputError(replace_all(e.what(), file.path().string(), name));
  }
}

} // namespace iarap::serve
