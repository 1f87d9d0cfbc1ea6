#include <stdio.h>
int main(void) { puts("dmbench: skeleton"); return 0; }
