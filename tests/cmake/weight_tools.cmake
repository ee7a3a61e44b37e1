# Weight tools (limit, normalize with locks, smooth, mirror, report): the core functions, and the
# document commands and script commands that run them.
dfm_test(test_weight_tools SOURCES test_weight_tools.cpp LIBS dfm_bind)
dfm_test(test_weight_tools_document SOURCES test_weight_tools_document.cpp LIBS dfm_scene)
# The weight brush (core/scene/weight_brush.h): its modes, locks, the document's strokes and paint-weights.
dfm_test(test_weight_brush SOURCES test_weight_brush.cpp LIBS dfm_scene)
