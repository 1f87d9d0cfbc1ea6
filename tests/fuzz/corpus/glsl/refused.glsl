//@technique b
//@param key int 0 4294967296 1
#include "a"
