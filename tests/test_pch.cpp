// The translation unit that builds tests/test_pch.h once (see tests/CMakeLists.txt).
