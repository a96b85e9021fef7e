// SPDX-License-Identifier: Apache-2.0
// Entry point of the SystemC test binary: libsystemc.so owns main() and calls sc_main,
// so GTest runs from here (not gtest_main). Each simulation runs in a forked child
// (harness.h), so this process never elaborates.
#include <gtest/gtest.h>

#include <systemc>

int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
