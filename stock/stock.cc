// placeholder until the module lands
#include "stock.h"
