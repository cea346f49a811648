// A shared library without the attend_plugin entry point: attend must refuse it.
extern "C" __attribute__((visibility("default"))) int not_an_attend_plugin() { return 42; }
