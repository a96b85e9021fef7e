// SPDX-License-Identifier: Apache-2.0
// The headers nearly every test file includes, parsed once a test binary into a
// precompiled header (tb/test_pch.cmake) instead of once a file: GTest alone is about
// 1.6 s of CPU a file. Only system and third-party headers: a project header here would
// rebuild every test file when it changes.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>
