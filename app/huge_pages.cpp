// The tool's heap is backed by transparent huge pages (glibc's tunable glibc.malloc.hugetlb=1, which
// madvises what malloc maps), unless the user set that tunable or the kernel has THP off. A precompute
// writes every array it allocates once (elements, intrinsic triangulation, factor), so its cost is largely
// first-touch page faults, and on the virtual machines iarap is measured on a fault is expensive: beetle
// (20K vertices), 1 thread, precompute 57 against 130 ms for original ARAP and 78 against 175 ms for iARAP;
// the 173K armadillo 1.2-1.6 against 2.0-2.4 s; peak memory +2% (issue 18, README "Performance").
//
// glibc reads GLIBC_TUNABLES in the dynamic loader, before any code of the program runs, so the tool sets
// it and executes itself again, once (the variable then names the tunable), from the executable's
// .preinit_array: before any library's constructor. Under valgrind (whose tools would lose the re-executed
// process) and when the exec fails, the tool goes on with ordinary pages. GLIBC_TUNABLES=glibc.malloc.hugetlb=0
// turns it off.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb";

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

void use_huge_pages(int, char** argv, char** envp) {
  const char* tunables = find_variable(envp, "GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, kTunable) != nullptr) return; // chosen, or already re-executed
  const char* preload = find_variable(envp, "LD_PRELOAD");
  if (preload != nullptr && std::strstr(preload, "vgpreload") != nullptr) return; // running under valgrind
  if (!transparent_huge_pages_available()) return;
  static char entry[1024];
  const int length = tunables != nullptr && *tunables != '\0'
                         ? std::snprintf(entry, sizeof entry, "GLIBC_TUNABLES=%s:%s=1", tunables, kTunable)
                         : std::snprintf(entry, sizeof entry, "GLIBC_TUNABLES=%s=1", kTunable);
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

__attribute__((section(".preinit_array"), used)) void (*const set_huge_pages)(int, char**, char**) = &use_huge_pages;

} // namespace
