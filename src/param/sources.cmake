# Sources of the param module (UV maps of disk-like surfaces), relative to src/.
list(APPEND IARAP_SOURCES
  param/boundary_loops.cpp param/triangle_frames.cpp param/disk_mesh.cpp
  param/lscm.cpp param/fixed_boundary_map.cpp param/injective_step.cpp
  param/map_distortion.cpp param/planar_cells.cpp param/param_options.cpp param/arap_parameterize.cpp
  param/uv_elastic_energy.cpp param/injectivity_barrier.cpp param/uv_problem.cpp
  param/write_uv_map.cpp param/render_uv_picture.cpp
  param/chart_segmentation.cpp param/chart_packing.cpp param/packing_bitmap.cpp param/uv_overlap.cpp param/uv_atlas.cpp
  param/texture_seam_charts.cpp)
