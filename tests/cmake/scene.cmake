# core/scene: the document, its file format, the script language and the default scene generator.
dfm_test(test_document SOURCES test_document.cpp LIBS dfm_scene)
