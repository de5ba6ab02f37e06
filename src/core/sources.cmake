# Sources of the core module, relative to src/.
list(APPEND IARAP_SOURCES core/threads.cpp core/version.cpp)
