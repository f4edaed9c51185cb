// loop_budget.glsl — whether the GL cut this invocation's loops short. Mesa's llvmpipe gives a
// shader invocation one budget of 65535 loop passes over all its loops and, once it is spent,
// ends every loop without a word. A loop of uProbePasses passes (kLoopProbePasses, set by the
// pass; a uniform, so it is not unrolled) run after the work then makes only one. A GL without
// such a limit never cuts. Used by raymarch.frag.glsl and volume_resolve.comp.glsl.

uniform int uProbePasses;

bool loopsWereCut() {
  int passes = 0;
  for (int k = 0; k < uProbePasses; ++k) ++passes;
  return passes < uProbePasses;
}
