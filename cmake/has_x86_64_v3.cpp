// Configure-time probe (CMakeLists.txt, FFSIM_ARCH=auto): exit 0 when the
// building machine runs x86-64-v3 code (AVX2, FMA, BMI1/2, F16C, MOVBE, LZCNT).
int main() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  __builtin_cpu_init();
  const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
                  __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("f16c") && __builtin_cpu_supports("movbe") &&
                  __builtin_cpu_supports("lzcnt");
  return v3 ? 0 : 1;
#else
  return 1;
#endif
}
