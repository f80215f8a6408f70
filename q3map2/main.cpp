#include <cstdio>

int main(int argc, char** argv) {
    std::fprintf(stderr, "q3map2: no stage is built yet\n");
    return 2;
}
