# Sources of the solver module, relative to src/.
list(APPEND IARAP_SOURCES)
