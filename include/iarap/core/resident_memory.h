// The process's resident memory, for the memory figures of `bench` and the run reports (issue 44).
#pragma once
#include <cstddef>

namespace iarap {

// The largest resident set the process has had so far (getrusage's ru_maxrss), in bytes.
std::size_t peak_resident_bytes();

// The resident set now (/proc/self/statm), in bytes; 0 where the file cannot be read.
std::size_t current_resident_bytes();

// Returns the heap's free pages to the system (glibc's malloc_trim over every arena): after a precompute
// freed its transient structures, what stays resident is what is held, not the high-water mark of a
// heap that keeps freed memory for reuse (app/malloc_settings.cpp sets a 128 MB trim threshold).
void release_free_heap();
// release_free_heap() on a mesh of at least 100K vertices, where the heap a phase freed is worth returning
// (each call walks every arena: milliseconds); nothing below. The precompute calls it after each phase
// that frees transients: its two threads allocate from heaps of their own (and arrays of 32 MB and more
// are mappings of their own), so one thread's freed memory would otherwise stay resident beside the other's
// new arrays.
void release_free_heap(std::ptrdiff_t vertices);

// With IARAP_MEMORY_TRACE set in the environment, writes "memory: PHASE resident R MB peak P MB (malloc in
// use M MB)" to stderr: where the precompute's peak happens, phase by phase, and how much of the resident
// set is live (the rest: freed memory malloc keeps, libraries, stacks). Otherwise nothing.
void trace_resident(const char* phase);

} // namespace iarap
