// A source that reaches into another folder by a relative path: refused.
#include "../model/view_samplers.h"
