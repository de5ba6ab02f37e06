#include "route_table.h"

#include "http_error.h"

#include <algorithm>

namespace iarap::serve {

void RouteTable::get(const std::string& path, httplib::Server::Handler handler) {
  server_.Get(path, std::move(handler));
  methods_[path].push_back("GET");
}

void RouteTable::post(const std::string& path, httplib::Server::Handler handler) {
  server_.Post(path, std::move(handler));
  methods_[path].push_back("POST");
}

void RouteTable::answer_other_methods_with_405() {
  for (const auto& [path, methods] : methods_) {
    std::string allow;
    for (const std::string& method : methods) allow += (allow.empty() ? "" : ", ") + method;
    const auto refuse = [path = path, allow](const httplib::Request& req, httplib::Response& res) {
      res.set_header("Allow", allow);
      throw HttpError(405, req.method + " is not allowed on " + path + "; use " + allow);
    };
    const auto has = [&methods = methods](const char* method) {
      return std::find(methods.begin(), methods.end(), method) != methods.end();
    };
    if (!has("GET")) server_.Get(path, refuse);
    if (!has("POST")) server_.Post(path, refuse);
    server_.Put(path, refuse);
    server_.Delete(path, refuse);
    server_.Patch(path, refuse);
  }
}

} // namespace iarap::serve
