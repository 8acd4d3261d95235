# ctest case public_api_detects: check-public-api.cmake counts what issue 32 counts and fails above the budget. A
# synthetic header of 4 public methods (2 overloads, an inline one, one after a private and a protected part), next to
# what must not count (constructors, destructor, operators, a nested class's methods, a typedef of a function pointer,
# declarations in comments, private and protected methods), is checked against budgets of 4 (pass) and 3 (fail).
#   cmake -DSCRIPT=<repo>/tests/check-public-api.cmake -DWORK_DIR=<dir> -P check-public-api-detects.cmake
cmake_minimum_required(VERSION 3.16)
if(NOT SCRIPT OR NOT WORK_DIR)
  message(FATAL_ERROR "SCRIPT and WORK_DIR must be set")
endif()

file(WRITE "${WORK_DIR}/vpCase.h" "/*!\n  \\class vpCase\n  not counted: void commented(int);\n*/
class VISP_EXPORT vpCase
{
public:
  //! not counted: void lineComment();
  typedef void (*vpCallback)(int);
  static constexpr int answer = 42;
  vpCase();
  explicit vpCase(int a);
  ~vpCase();
  vpCase &operator=(const vpCase &other);
  bool operator==(const vpCase &other) const;
  void set(int a);
  void set(double a);
  int get() const { return m_a; }
  class VISP_EXPORT vpNested
  {
  public:
    void nestedMethod();
  };
  friend void befriended(vpCase &c);

private:
  void hidden();

protected:
  void inherited();

public:
  /* not counted: void blockComment(); */ void last(const vpCase &c) /* const */;

private:
  int m_a;
};
")

set(wrong "")
function(expect name verdict limit)
  execute_process(COMMAND ${CMAKE_COMMAND} -DINCLUDE_DIR=${WORK_DIR} -DCLASSES=vpCase
                          -DLIMIT=${limit} -P ${SCRIPT}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(verdict STREQUAL "pass" AND NOT rc EQUAL 0)
    set(wrong "${wrong}\n${name}: should pass, the check failed:\n${err}" PARENT_SCOPE)
  elseif(verdict STREQUAL "fail" AND rc EQUAL 0)
    set(wrong "${wrong}\n${name}: should fail (4 public methods, budget ${limit}), the check passed:\n${out}" PARENT_SCOPE)
  elseif(verdict STREQUAL "pass" AND NOT "${out}${err}" MATCHES "vpCase: 4 public methods")
    set(wrong "${wrong}\n${name}: should count 4 public methods (set, set, get, last):\n${out}${err}" PARENT_SCOPE)
  endif()
endfunction()

expect(within_budget pass 4)
expect(above_budget fail 3)

if(wrong)
  message(FATAL_ERROR "check-public-api.cmake gave a wrong verdict:${wrong}")
endif()
