// `iarap serve [MESH...]`: the interactive web viewer. An HTTP server (cpp-httplib) serves the app in web/
// and an API over one deformation session; see serve/api_routes.h for the routes.
#include "command_registry.h"
#include "serve/api_routes.h"
#include "serve/private_temp_dir.h"
#include "serve/shared_session.h"
#include "serve/static_files.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"

#include <httplib.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <iostream>
#include <memory>
#include <pthread.h>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>

#ifndef IARAP_WEB_DIR
#define IARAP_WEB_DIR ""
#endif
#ifndef IARAP_WEB_FROM_BIN
#define IARAP_WEB_FROM_BIN ""
#endif

namespace iarap::cli {
namespace {

// The write end of the stop pipe (set once by stop_signal_pipe).
int stop_pipe_write = -1;

// Async-signal-safe: one byte to the pipe (a full pipe already holds a stop request).
void request_stop() {
  const int saved = errno;
  const char byte = 1;
  [[maybe_unused]] const ssize_t written = ::write(stop_pipe_write, &byte, 1);
  errno = saved;
}

extern "C" void on_stop_signal(int) {
  request_stop();
}

// The pipe's read end, with SIGINT and SIGTERM handled by on_stop_signal from now on.
int stop_signal_pipe() {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw Error("serve: cannot create the stop pipe");
  stop_pipe_write = fds[1];
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (const int signal : {SIGINT, SIGTERM}) ::sigaction(signal, &action, nullptr);
  return fds[0];
}

struct ServeArguments {
  std::vector<std::string> meshes;
  int port = 8080;
  std::string host = "127.0.0.1";
  std::string app_dir = serve::default_web_root(IARAP_WEB_FROM_BIN, IARAP_WEB_DIR).string();
  double max_upload_mb = 64;
  int threads = 0;
  bool verbose = false;
};

bool is_loopback(const std::string& host) {
  return host == "127.0.0.1" || host == "localhost" || host == "::1";
}

// Names clients see: the file name, made unique with "#2", "#3"... when two paths share it.
std::vector<serve::ServerMesh> server_meshes(const std::vector<std::string>& paths) {
  std::vector<serve::ServerMesh> meshes;
  for (const auto& path : paths) {
    const std::string base = std::filesystem::path(path).filename().string();
    std::string name = base;
    for (int n = 2; std::any_of(meshes.begin(), meshes.end(), [&](const auto& m) { return m.name == name; });
         ++n)
      name = base + "#" + std::to_string(n);
    meshes.push_back({name, path});
  }
  return meshes;
}

void run_serve(const ServeArguments& args, bool host_given) {
  serve::ServeConfig config;
  config.app_dir = args.app_dir;
  if (config.app_dir.empty() || !std::filesystem::is_regular_file(config.app_dir / "index.html"))
    throw CLI::ValidationError("--app-dir", "no index.html in \"" + args.app_dir +
                                                "\"; give the repository's web/ folder");
  if (!std::filesystem::is_regular_file(config.app_dir / "node_modules/three/build/three.module.js")) {
    std::cerr << "serve: warning: " << (config.app_dir / "node_modules/three").string()
              << " is missing; run `npm ci --prefix web` or the page cannot load three.js\n";
  }
  if (!(args.max_upload_mb > 0 && args.max_upload_mb <= 4096))
    throw CLI::ValidationError("--max-upload-mb", "must be in (0, 4096]");
  config.max_upload_bytes = static_cast<std::size_t>(args.max_upload_mb * (1 << 20));
  config.meshes = server_meshes(args.meshes);
  config.verbose = args.verbose;
  set_thread_count(args.threads);

  // SIGINT / SIGTERM stop the server through a handler that writes one byte to a pipe, read by one thread.
  // A handler serves whichever thread the kernel picks; blocking the signals and taking them with sigwait
  // did not, because OpenBLAS starts its thread pool when the library loads, before main, with the
  // default mask: a SIGTERM delivered to one of its threads ended the process.
  const int stop_pipe = stop_signal_pipe();

  serve::SharedSession session;
  if (!config.meshes.empty()) {
    serve::load_server_mesh(session, config.meshes.front());
    const serve::MeshSummary summary = session.read([](const serve::Session& s) { return s.mesh_summary(); });
    std::cerr << "serve: loaded " << summary.name << " (" << summary.vertices << " vertices, "
              << summary.faces << " faces)\n";
  }
  if (host_given && !is_loopback(args.host)) {
    std::cerr << "serve: WARNING: listening on " << args.host
              << " lets other machines reach this server; it has no authentication. Use only on a trusted "
                 "network.\n";
  }

  serve::PrivateTempDir temp;
  httplib::Server server;
  // A worker thread serves one connection until it closes or idles past the keep-alive timeout, so idle
  // keep-alive connections would starve httplib's default pool (8 threads here) under a burst. Requests
  // mostly wait on the session mutex, so many threads cost little. httplib owns the queue it is given.
  server.new_task_queue = [] { return new httplib::ThreadPool(64); };
  server.set_keep_alive_max_count(1000); // one browser connection carries a whole drag
  server.set_keep_alive_timeout(2);
  // httplib's default also sets SO_REUSEPORT, which would let a second server share the port silently.
  socket_t listening = INVALID_SOCKET;
  server.set_socket_options([&listening](socket_t sock) {
    const int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    listening = sock;
  });
  const int port = args.port == 0 ? server.bind_to_any_port(args.host)
                                  : (server.bind_to_port(args.host, args.port) ? args.port : -1);
  if (port < 0)
    throw Error("cannot listen on " + args.host + ":" + std::to_string(args.port) +
                " (in use, or not an address of this machine)");
  // Debian's httplib listens with a backlog of 5: a burst of more new connections (20 at once from a
  // script) overflowed it, and clients got resets or waited out SYN retries. Listening again on the
  // listening socket sets a new backlog (Linux).
  if (listening != INVALID_SOCKET) ::listen(listening, 128);
  if (!host_given || is_loopback(args.host)) {
    for (const char* name : {"127.0.0.1", "localhost", "[::1]"})
      config.allowed_hosts.push_back(std::string(name) + ":" + std::to_string(port));
  }
  serve::register_routes(server, config, session, temp);

  std::thread signal_thread([&server, &session, stop_pipe] {
    char byte = 0;
    while (::read(stop_pipe, &byte, 1) < 0 && errno == EINTR) {
    }
    session.frames().close(); // frame waits answer at once, so that the workers end
    server.stop();
  });
  const std::string shown_host = args.host.find(':') != std::string::npos ? "[" + args.host + "]" : args.host;
  std::cout << "iarap serve: open http://" << shown_host << ":" << port << "/ in a browser (Ctrl-C stops)"
            << std::endl;
  const bool clean = server.listen_after_bind();
  request_stop(); // wakes the signal thread if listening failed
  signal_thread.join();
  if (!clean) throw Error("the server stopped listening unexpectedly");
  std::cerr << "serve: stopped\n";
}

const bool serve_command_registered = register_command(
    {"serve", [](CLI::App& app) {
       auto args = std::make_shared<ServeArguments>();
       auto* sub = app.add_subcommand(
           "serve", "Interactive web viewer: drag handles and watch the energies deform a mesh");
       sub->add_option("meshes", args->meshes,
                       "Meshes the page can load (OBJ, OFF, PLY, STL; tetrahedral .mesh, .node/.ele, .msh "
                       "shown by their boundary); the first is loaded")
           ->check(CLI::ExistingFile);
       sub->add_option("--port", args->port, "TCP port (0: any free port)")->check(CLI::Range(0, 65535));
       auto* host =
           sub->add_option("--host", args->host, "Address to listen on (default 127.0.0.1, loopback only)");
       sub->add_option("--app-dir", args->app_dir,
                       "Folder of the web app (index.html, src/, node_modules/three)");
       sub->add_option("--max-upload-mb", args->max_upload_mb, "Largest accepted request body, in MiB");
       sub->add_option("--threads", args->threads, "Solver threads (0: all cores)")
           ->check(CLI::NonNegativeNumber);
       sub->add_flag("--verbose", args->verbose, "Log every request to stderr");
       sub->callback([args, host] { run_serve(*args, host->count() > 0); });
     }});

} // namespace
} // namespace iarap::cli
