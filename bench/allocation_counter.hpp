#pragma once
/// \file allocation_counter.hpp
/// How many C++ heap allocations (operator new) this process has made so far (allocation_counter.cpp).
long long heap_allocations();
