// A base header that includes a module above it: the order check must refuse it.
#pragma once
#include "icgp/tracker/tracker.h"
