// The translation unit cmake/module_pch.h is precompiled with (DeformHelpers.cmake: dfm_module_pch).
