# Sources of the intrinsic module, relative to src/.
list(APPEND IARAP_SOURCES)
