# Sources of the registration module (non-rigid ICP with the ARAP energy as regularizer), relative to src/.
list(APPEND IARAP_SOURCES registration/point_index.cpp registration/surface_normals.cpp
  registration/closest_surface_point.cpp registration/rigid_alignment.cpp registration/registration_target.cpp
  registration/correspondences.cpp registration/prealign.cpp registration/register.cpp
  registration/sample_surface.cpp)
