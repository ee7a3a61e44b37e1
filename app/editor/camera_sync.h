#pragma once
// The document stores the camera as eye/target/up (saved with the scene); the viewport works with
// the orbit camera. These convert between the two without losing the view.
#include "core/scene/document.h"
#include "core/view/camera.h"

namespace dfm::editor {

dfm::Camera to_document_camera(const view::Camera& c);
// Keeps c's viewport size and scene radius; takes eye, target, up, field of view and projection.
void from_document_camera(const dfm::Camera& d, view::Camera& c);

}  // namespace dfm::editor
