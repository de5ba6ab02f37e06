# Sources of the laplacian module, relative to src/.
list(APPEND IARAP_SOURCES)
