/* Generator headers, one per generator; included by banyan.h. */
#ifndef BANYAN_GENERATORS_H
#define BANYAN_GENERATORS_H
#include "hosts.h"
#include "textures.h"
#include "segments.h"
#include "keyaki.h"
#include "ivy.h"
#include "roots.h"
#include "lod.h"
#include "compat.h"
#endif
