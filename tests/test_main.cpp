// The test runner. ctest runs one test case per entry through --test-case=NAME; a name the filter
// cannot match (CMake splits names at ';', for example) would otherwise select nothing and pass.
// A listener counts the cases that passed the filters, and a run that selects none fails.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>

#ifdef LAMINA_GL_TEST_MAIN
#include "glsl/gl_runner.h"
#endif

namespace {

int cases_selected = -1;  // -1 until a test run ends (listing options end without one)

struct SelectionCounter : doctest::IReporter {
  explicit SelectionCounter(const doctest::ContextOptions&) {}
  void report_query(const doctest::QueryData&) override {}
  void test_run_start() override {}
  void test_run_end(const doctest::TestRunStats& stats) override {
    cases_selected = int(stats.numTestCasesPassingFilters);
  }
  void test_case_start(const doctest::TestCaseData&) override {}
  void test_case_reenter(const doctest::TestCaseData&) override {}
  void test_case_end(const doctest::CurrentTestCaseStats&) override {}
  void test_case_exception(const doctest::TestCaseException&) override {}
  void subcase_start(const doctest::SubcaseSignature&) override {}
  void subcase_end() override {}
  void log_assert(const doctest::AssertData&) override {}
  void log_message(const doctest::MessageData&) override {}
  void test_case_skipped(const doctest::TestCaseData&) override {}
};

REGISTER_LISTENER("selection_counter", 1, SelectionCounter);

int run_tests(int argc, char** argv) {
  doctest::Context context(argc, argv);
  int result = context.run();
  if (context.shouldExit()) return result;
  if (result == 0 && cases_selected == 0) {
    std::fprintf(stderr, "no test case matches the filters given: nothing was tested\n");
    return 1;
  }
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  const int status = run_tests(argc, argv);
#ifdef LAMINA_GL_TEST_MAIN
  lamina::gltest::check_leaks_now();  // while Mesa's threads are idle (see gl_runner.h)
#endif
  return status;
}
