# Sources of the scene module, relative to src/.
list(APPEND IARAP_SOURCES)
