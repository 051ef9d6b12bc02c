#pragma once
// EXPECT_CONTAINS(text, part): a non-fatal failure, printing the text, unless `part` occurs in
// `text` (a message checked for what it names).

#include <gtest/gtest.h>

#include <string>

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)
