// Placeholder entry until the editor lands (replaced by the editor module).
#include <cstdio>
int main() { std::puts("deform-editor: not built yet"); return 1; }
