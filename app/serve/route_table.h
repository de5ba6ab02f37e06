// Route registration that remembers each path's methods, so that another method on a known path is
// answered 405 with Allow instead of httplib's 404.
#pragma once
#include <httplib.h>

#include <map>
#include <string>
#include <vector>

namespace iarap::serve {

class RouteTable {
public:
  explicit RouteTable(httplib::Server& server) : server_(server) {}

  void get(const std::string& path, httplib::Server::Handler handler);
  void post(const std::string& path, httplib::Server::Handler handler);
  // Registers, for every path seen, a handler of the other methods (GET, POST, PUT, DELETE, PATCH) that
  // throws HttpError 405 after setting Allow. Call once, after the routes.
  void answer_other_methods_with_405();

private:
  httplib::Server& server_;
  std::map<std::string, std::vector<std::string>> methods_;
};

} // namespace iarap::serve
