# Tests of the jobs module (the pipelines every front-end calls), relative to tests/.
list(APPEND IARAP_TEST_SOURCES jobs/deform_job_test.cpp jobs/volume_deform_test.cpp)
