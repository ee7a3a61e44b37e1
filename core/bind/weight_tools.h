#pragma once
// The weight tools artists expect (Blender's weight paint menu), free functions on the bind's
// #V x #handles weights: limit total influences smoothly, normalize with locked handles, smooth, mirror,
// and a report of handles with no weight. Each keeps BBW's properties (Jacobson 2013, 4.3.1): weights
// in [0, 1] (4.6), partition of unity (4.5), and the values the bind fixed at the handles (4.3, 4.4):
// the rows of weight_constraints.h's vertices are never changed. The Document's weights_* commands
// and the script's weights-* run them as undoable edits.
#include "core/bind/weight_constraints.h"
#include "core/bind/weight_limit.h"
#include "core/bind/weight_mirror.h"
#include "core/bind/weight_normalize.h"
#include "core/bind/weight_report.h"
#include "core/bind/weight_smooth.h"
