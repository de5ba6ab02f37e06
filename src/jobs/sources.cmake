# Sources of the jobs module (the pipelines every front-end calls), relative to src/.
list(APPEND IARAP_SOURCES jobs/deform_job.cpp jobs/read_deform_scene.cpp jobs/tetrahedralize_inside.cpp
  jobs/volume_scene.cpp)
