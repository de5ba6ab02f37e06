list(APPEND IARAP_TEST_SOURCES intrinsic/intrinsic_delaunay_test.cpp intrinsic/hand_derived_test.cpp
     intrinsic/upper_half_angle_test.cpp intrinsic/tufted_cover_test.cpp intrinsic/tufted_arap_test.cpp)
