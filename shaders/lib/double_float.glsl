// Double-float ("float-float") sums: a value is hi + lo with |lo| <= ulp(hi) / 2, about 48
// significant bits from float32 arithmetic alone (no shaderFloat64). Knuth's TwoSum and Dekker's
// FastTwoSum are error-free only where float addition rounds to nearest; Vulkan's default is
// round-to-nearest-even or round-toward-zero, implementation-defined, so this file declares
// RoundingModeRTE for 32-bit floats in every shader that includes it (below), and device
// selection refuses a device without shaderRoundingModeRTEFloat32 (gpu/context.h); the sums are Joldes,
// Muller and Popescu 2017, "Tight and rigorous error bounds for basic building blocks of
// double-word arithmetic" (Alg. 4 and 6: relative error <= 2u^2 and 3u^2, u = 2^-24).
// `precise` keeps the driver from contracting or reassociating them ((a + b) - a is not b):
// without it lavapipe folds the low parts to 0 and the sums drift as plain float32 sums do.
// All functions work per component. CPU readers combine hi + lo in double.
#ifndef AMRVK_DOUBLE_FLOAT_GLSL
#define AMRVK_DOUBLE_FLOAT_GLSL

// OpExecutionMode RoundingModeRTE (4462) 32, capability RoundingModeRTE (4467), from
// SPV_KHR_float_controls (core in SPIR-V 1.4): every float32 addition of the entry point rounds to
// nearest even.
#extension GL_EXT_spirv_intrinsics : require
spirv_execution_mode(extensions = ["SPV_KHR_float_controls"], capabilities = [4467], 4462, 32);

// s = fl(a + b) and e = (a + b) - s exactly, for any a, b (TwoSum, 6 additions).
void twoSum(vec4 a, vec4 b, out vec4 s, out vec4 e) {
    precise vec4 sum = a + b;
    precise vec4 bPart = sum - a;
    precise vec4 err = (a - (sum - bPart)) + (b - bPart);
    s = sum;
    e = err;
}

// The same where |a| >= |b| (or a == 0) per component (FastTwoSum, 3 additions).
void fastTwoSum(vec4 a, vec4 b, out vec4 s, out vec4 e) {
    precise vec4 sum = a + b;
    precise vec4 err = b - (sum - a);
    s = sum;
    e = err;
}

// hi + lo += x (a float per component), renormalised: |lo| <= ulp(hi) / 2.
void addDoubleFloat(inout vec4 hi, inout vec4 lo, vec4 x) {
    vec4 s, e;
    twoSum(hi, x, s, e);
    precise vec4 t = lo + e;
    fastTwoSum(s, t, hi, lo);
}

// hi + lo += xHi + xLo (a double-float), renormalised: |lo| <= ulp(hi) / 2.
void addDoubleFloat(inout vec4 hi, inout vec4 lo, vec4 xHi, vec4 xLo) {
    vec4 sh, sl, th, tl, vh, vl;
    twoSum(hi, xHi, sh, sl);
    twoSum(lo, xLo, th, tl);
    precise vec4 c = sl + th;
    fastTwoSum(sh, c, vh, vl);
    precise vec4 w = tl + vl;
    fastTwoSum(vh, w, hi, lo);
}

#endif
