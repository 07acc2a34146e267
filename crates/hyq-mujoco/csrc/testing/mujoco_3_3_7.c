/* A stand-in for another MuJoCo version's library, for the tests of the version check: it
 * answers mj_version() and mj_versionString() as MuJoCo 3.3.7 would, and has nothing else. */
int mj_version(void) { return 3003007; }
const char* mj_versionString(void) { return "3.3.7"; }
