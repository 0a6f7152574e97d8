#include <stdio.h>
#include "illum/illum.h"
int main(void) { puts("illum " IL_VERSION_STRING); return 0; }
