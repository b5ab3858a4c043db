"""tools/tune: the motor profile calculator (motortune) and its examples (docs/tune.md)."""
