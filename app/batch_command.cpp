// `iarap batch MANIFEST [...]`: runs a manifest of jobs on local worker processes or a Dask cluster. The
// runner is Python (python/iarap/batch.py, on Debian's python3-distributed: Dask does the scheduling, the
// retries and the recovery from dead workers); this command hands its arguments to it, with the tool itself
// as the jobs' executable, so that `iarap batch` works wherever `iarap` does.
#include "command_registry.h"

#include "iarap/core/errors.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

namespace iarap::cli {
namespace {

void run_batch(const std::vector<std::string>& arguments) {
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw Error("iarap batch: cannot find the running executable (/proc/self/exe)");
  // The build tree keeps the package beside the tool (build/python/iarap); an install puts it where
  // python3 finds it by itself.
  const std::filesystem::path package = executable.parent_path() / "python";
  if (std::filesystem::is_regular_file(package / "iarap" / "batch.py", error)) {
    const char* old = std::getenv("PYTHONPATH");
    const std::string path = package.string() + (old && *old ? ":" + std::string(old) : "");
    ::setenv("PYTHONPATH", path.c_str(), 1);
  }
  ::setenv("IARAP_CLI", executable.c_str(), 1);
  std::vector<std::string> words = {"python3", "-m", "iarap.batch"};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  // Debian's interpreter first: python3-distributed and python3-numpy are its packages, whatever python3
  // comes first on PATH (a pyenv or a venv lacks them). Named by its full path in argv[0] too: Python
  // derives sys.executable, which starts the Dask worker processes, from it.
  static char debian_python[] = "/usr/bin/python3";
  if (::access(debian_python, X_OK) == 0) {
    argv[0] = debian_python;
    ::execv(debian_python, argv.data());
  }
  ::execvp("python3", argv.data());
  throw Error(
      std::string("iarap batch runs on Python 3 (python3-distributed, the iarap package): cannot start "
                  "python3: ") +
      std::strerror(errno));
}

const bool batch_command_registered =
    register_command({"batch", [](CLI::App& app) {
                        auto* sub = app.add_subcommand(
                            "batch", "Run a manifest (JSON / CSV) of deform and param jobs on local "
                                     "worker processes or a Dask cluster (python3 -m iarap.batch; "
                                     "'iarap batch --help' for its options)");
                        sub->allow_extras();
                        sub->set_help_flag(); // --help goes to the Python runner, which knows the options
                        sub->callback([sub] { run_batch(sub->remaining()); });
                      }});

} // namespace
} // namespace iarap::cli
