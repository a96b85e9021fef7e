// SPDX-License-Identifier: Apache-2.0
// Entry point of the stage-agreement tests (test_stages.cpp): libsystemc.so owns main()
// and calls sc_main, so GTest runs from here. SystemC runs only in forked children.
#include <gtest/gtest.h>

#include <systemc>

int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
