// Which files GET may read (app/serve/static_files.h): the app's own files and three.js's modules, with
// their content types; traversal, hidden files, other folders and links out of the app folder refused.
#include "../../app/serve/static_files.h" // the tool's sources: tests/ is on the include path, app/ is not
#include "test_support.h"

#include <gtest/gtest.h>

#include <fstream>

namespace {

using iarap::serve::resolve_static_file;

class ServeStaticFiles : public ::testing::Test {
protected:
  void SetUp() override {
    root_ = iarap::test::temp_dir("serve_static");
    app_ = root_ / "web";
    for (const char* file : {"index.html", "style.css", "favicon.ico", "notes.txt", ".hidden.js",
                             "src/main.js", "src/view/draw.js", "node_modules/three/build/three.module.js",
                             "node_modules/three/examples/jsm/controls/OrbitControls.js",
                             "node_modules/three/src/secret.js", "node_modules/other/build/x.js"})
      write(app_ / file);
    write(root_ / "outside.js"); // beside the app folder, not in it
    std::filesystem::create_symlink(root_ / "outside.js", app_ / "src" / "link.js");
  }
  void TearDown() override { std::filesystem::remove_all(root_); }

  static void write(const std::filesystem::path& path) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << "x";
  }

  std::optional<std::string> type_of(const std::string& request) const {
    const auto file = resolve_static_file(app_, request);
    if (!file) return std::nullopt;
    return file->content_type;
  }

  std::filesystem::path root_, app_;
};

} // namespace

TEST_F(ServeStaticFiles, ServesTheAppWithItsContentTypes) {
  EXPECT_EQ(type_of("/"), "text/html; charset=utf-8");
  EXPECT_EQ(type_of("/index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(type_of("/style.css"), "text/css; charset=utf-8");
  EXPECT_EQ(type_of("/favicon.ico"), "image/x-icon");
  EXPECT_EQ(type_of("/src/main.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(type_of("/src/view/draw.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(type_of("/node_modules/three/build/three.module.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(type_of("/node_modules/three/examples/jsm/controls/OrbitControls.js"),
            "text/javascript; charset=utf-8");
  const auto index = resolve_static_file(app_, "/");
  ASSERT_TRUE(index.has_value());
  EXPECT_EQ(index->path, std::filesystem::canonical(app_ / "index.html"));
}

TEST_F(ServeStaticFiles, RefusesTraversal) {
  for (const char* request :
       {"/../outside.js", "/src/../index.html", "/src/../../outside.js", "/./index.html", "/..",
        "/src/%2e%2e/index.html", "/src//main.js", "//etc/passwd", "index.html", ""})
    EXPECT_FALSE(resolve_static_file(app_, request).has_value()) << request;
}

TEST_F(ServeStaticFiles, RefusesLinksOutOfTheAppFolder) {
  EXPECT_FALSE(resolve_static_file(app_, "/src/link.js").has_value());
}

TEST_F(ServeStaticFiles, UnknownHiddenAndOtherFilesAreNotFound) {
  for (const char* request : {"/missing.js", "/src/missing.js", "/.hidden.js", "/notes.txt",
                              "/node_modules/three/src/secret.js", "/node_modules/other/build/x.js", "/src"})
    EXPECT_FALSE(resolve_static_file(app_, request).has_value()) << request;
  EXPECT_FALSE(resolve_static_file(root_ / "no_such_folder", "/index.html").has_value());
}
