mod rpy_tests;
