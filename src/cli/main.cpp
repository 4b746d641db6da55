#include <cstdio>

int main() {
  std::puts("lpsim: commands are being built");
  return 0;
}
