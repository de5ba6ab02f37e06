// The tool's malloc settings, chosen for a precompute that writes every array it allocates once
// (elements, intrinsic triangulation, factor): its cost is largely first-touch page faults, and on the
// virtual machines iarap is measured on a 4 KB fault costs tens of microseconds.
// - glibc.malloc.hugetlb=1: transparent huge pages for what malloc maps (beetle, 1 thread, warm: precompute
//   57 against 130 ms for original ARAP, 78 against 175 ms for iARAP; the 173K armadillo 1.2-1.6 against
//   2.0-2.4 s; peak memory +2%).
// - mmap_threshold 32 MB, top_pad 64 MB, trim_threshold 128 MB: arrays below 32 MB come from the heap,
//   which grows in 64 MB steps (whole huge pages) and keeps what is freed for the next array, instead of
//   each array being a fresh mapping of its own, faulted in 4 KB pages at its unaligned ends and unmapped
//   when freed. glibc's own threshold adapts the same way, but only after a first large free: the first
//   precompute of a process paid it. Beetle, first precompute of a `deform`: 4,800-5,900 page faults ->
//   700-1,100; `bench` rounds, 1 thread: the first round 103-163 -> 63-66 ms (original ARAP), 108-121 ->
//   77-81 ms (iARAP), later rounds unchanged; 2 threads, later rounds: 80-84 -> 53-56 ms (original ARAP),
//   100-104 -> 70-77 ms (iARAP); peak memory +1-2 MB (issue 18, docs/performance.md).
//
// glibc reads GLIBC_TUNABLES in the dynamic loader, before any code of the program runs, so the tool sets
// it and executes itself again, once (the variable then names glibc.malloc.hugetlb), from the executable's
// .preinit_array: before any library's constructor. A tunable the user set is kept as set, and one who
// sets glibc.malloc.hugetlb (GLIBC_TUNABLES=glibc.malloc.hugetlb=0 turns huge pages off) gets no other
// setting of the tool's. Under valgrind (whose tools would lose the re-executed process), when the kernel
// has THP off and when the exec fails, the tool goes on with glibc's defaults.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace {

constexpr const char* kHugePages = "glibc.malloc.hugetlb";
// What the tool sets besides huge pages (see the top of the file), each unless the user set it.
constexpr const char* kHeapSettings[] = {"glibc.malloc.mmap_threshold=33554432",
                                         "glibc.malloc.top_pad=67108864",
                                         "glibc.malloc.trim_threshold=134217728"};

// False when /sys says "[never]" (or cannot be read): malloc's advice would change nothing.
bool transparent_huge_pages_available() {
  const int fd = ::open("/sys/kernel/mm/transparent_hugepage/enabled", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  char text[128] = {};
  const ssize_t n = ::read(fd, text, sizeof text - 1);
  ::close(fd);
  return n > 0 && std::strstr(text, "[never]") == nullptr;
}

// The value of NAME in envp (the process's environment as handed to .preinit_array functions: getenv may not
// see it yet there), or nullptr.
const char* find_variable(char** envp, const char* name) {
  const size_t length = std::strlen(name);
  for (char** e = envp; e != nullptr && *e != nullptr; ++e)
    if (std::strncmp(*e, name, length) == 0 && (*e)[length] == '=') return *e + length + 1;
  return nullptr;
}

// True when the colon-separated list `tunables` sets the tunable that `setting` ("name=value") names.
bool sets_tunable(const char* tunables, const char* setting) {
  const size_t name_length = std::strcspn(setting, "=");
  for (const char* at = tunables; at != nullptr && *at != '\0';) {
    if (std::strncmp(at, setting, name_length) == 0 && at[name_length] == '=') return true;
    at = std::strchr(at, ':');
    if (at != nullptr) ++at;
  }
  return false;
}

void use_malloc_settings(int, char** argv, char** envp) {
  const char* tunables = find_variable(envp, "GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, kHugePages) != nullptr)
    return; // chosen, or already re-executed
  const char* preload = find_variable(envp, "LD_PRELOAD");
  if (preload != nullptr && std::strstr(preload, "vgpreload") != nullptr) return; // running under valgrind
  if (!transparent_huge_pages_available()) return;
  static char entry[2048];
  const bool has_user_tunables = tunables != nullptr && *tunables != '\0';
  int length = std::snprintf(entry, sizeof entry, "GLIBC_TUNABLES=%s%s%s=1",
                             has_user_tunables ? tunables : "", has_user_tunables ? ":" : "", kHugePages);
  for (const char* setting : kHeapSettings)
    if (length > 0 && length < static_cast<int>(sizeof entry) && !sets_tunable(tunables, setting))
      length += std::snprintf(entry + length, sizeof entry - static_cast<size_t>(length), ":%s", setting);
  if (length <= 0 || length >= static_cast<int>(sizeof entry)) return;
  // The same environment with GLIBC_TUNABLES replaced (or added); this process's own is left untouched.
  size_t count = 0;
  while (envp != nullptr && envp[count] != nullptr) ++count;
  char** environment = static_cast<char**>(std::calloc(count + 2, sizeof(char*)));
  if (environment == nullptr) return;
  size_t k = 0;
  for (size_t i = 0; i < count; ++i)
    if (std::strncmp(envp[i], "GLIBC_TUNABLES=", 15) != 0) environment[k++] = envp[i];
  environment[k] = entry;
  ::execve("/proc/self/exe", argv, environment);
  std::free(environment); // the exec failed: go on with ordinary pages
}

__attribute__((section(".preinit_array"),
               used)) void (*const set_malloc_settings)(int, char**, char**) = &use_malloc_settings;

} // namespace
