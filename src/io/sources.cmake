# Sources of the io module, relative to src/.
list(APPEND IARAP_SOURCES)
