/* Every stage function a backend's entry points call, in one include. Backends include their
   compat.h first, then this. */
#ifndef PM_STAGES_H
#define PM_STAGES_H

#include "kernel_globals.h"
#include "kernel_list.h"
#include "camera_pass.h"
#include "film.h"
#include "film_layers.h"
#include "gather.h"
#include "final_gather.h"
#include "path_trace.h"
#include "bias_control.h"
#include "photon_footprint.h"
#include "footprint_scale.h"
#include "photon_map_stage.h"
#include "photon_trace.h"
#include "radiosity_gather.h"
#include "radiosity_interpolate.h"
#include "radiosity_light.h"
#include "radiosity_links.h"
#include "radiosity_bias_probe.h"
#include "radix_sort.h"
#include "layout_probe.h"

#endif
