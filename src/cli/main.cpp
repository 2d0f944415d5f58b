#include <cstdio>
int main() { std::puts("particles " PARTICLES_VERSION); return 0; }
