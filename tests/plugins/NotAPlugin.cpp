// A shared library that is not a Spindrift plugin (exports no factory): `libs` must refuse it.
extern "C" int spindriftTestNotAPlugin() { return 42; }
