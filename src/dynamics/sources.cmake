# Sources of the dynamics module (implicit Euler on the ARAP energy, lumped masses), relative to src/.
list(APPEND IARAP_SOURCES dynamics/vertex_masses.cpp dynamics/simulation.cpp)
