// tetrahedralize_inside (volume_deform.h): TetGen run as an external program on a private copy of the
// surface.
#include "iarap/core/errors.h"
#include "iarap/io/read_tet_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/jobs/volume_deform.h"
#include "iarap/mesh/validate.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

extern char** environ;

namespace iarap {

namespace {

// A folder of this process's own (mkdtemp, mode 0700), removed with everything in it at scope exit.
class ScratchFolder {
public:
  ScratchFolder() {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/iarap-tetgen-XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr)
      throw InputError("--volume: cannot create a scratch folder for tetgen under " + pattern);
    path_ = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::string& path() const { return path_; }

private:
  std::string path_;
};

// The last `count` lines of a text file (what a failing program printed).
std::string last_lines(const std::string& path, int count) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  std::string out;
  for (size_t k = lines.size() > static_cast<size_t>(count) ? lines.size() - count : 0; k < lines.size(); ++k)
    out += "\n  " + lines[k];
  return out;
}

// Runs `program -switches input` (no shell) with its output going to log; returns its wait status.
int run_tetgen(const TetgenOptions& options, const std::string& input, const std::string& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  const std::string flag = "-" + options.switches;
  std::vector<char*> argv = {const_cast<char*>(options.program.c_str()), const_cast<char*>(flag.c_str()),
                             const_cast<char*>(input.c_str()), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, options.program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0)
    throw InputError("--volume needs TetGen's program '" + options.program +
                     "', which could not be run; on Debian: apt-get install tetgen");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw InputError("--volume: lost track of the tetgen process");
  return status;
}

} // namespace

TetMesh tetrahedralize_inside(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                              const TetgenOptions& options) {
  const ScratchFolder folder;
  const std::string input = folder.path() + "/surface.off", log = folder.path() + "/tetgen.log";
  write_off(input, V, F);
  const int status = run_tetgen(options, input, log);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::ostringstream what;
    if (WIFEXITED(status))
      what << "exit status " << WEXITSTATUS(status);
    else
      what << "signal " << WTERMSIG(status);
    throw InputError(
        "--volume: tetgen -" + options.switches + " failed on the surface (" + what.str() +
        "; a self-intersecting or open surface cannot be tetrahedralized); it printed:" + last_lines(log, 6));
  }
  TetMesh tets = read_tet_mesh(folder.path() + "/surface.1.ele");
  // -pY keeps every surface vertex, first and in order, at its 17-digit coordinates: check, then take V's.
  const double tolerance = 1e-12 * bounding_box_diagonal(V);
  bool kept = tets.V.rows() >= V.rows();
  for (Eigen::Index v = 0; kept && v < V.rows(); ++v) kept = (tets.V.row(v) - V.row(v)).norm() <= tolerance;
  const Eigen::Index boundary = tet_boundary_faces(tets.T).rows();
  if (!kept || boundary != F.rows())
    throw InputError("--volume: tetgen -" + options.switches + " did not keep the surface (" +
                     std::to_string(tets.V.rows()) + " points for " + std::to_string(V.rows()) +
                     " surface vertices, " + std::to_string(boundary) + " boundary faces for " +
                     std::to_string(F.rows()) + "); give switches with -Y");
  tets.V.topRows(V.rows()) = V;
  return tets;
}

} // namespace iarap
