#!/usr/bin/env python3
"""scripts/function_size_screen.py: the screen may let a unit through unparsed only when none of
its long blocks can be a function's body. Each case builds a source around a block of 61 lines
(the screen's minimum here: 56) and says whether the screen must flag it."""
import io
import os
import sys
import unittest
from contextlib import redirect_stderr, redirect_stdout
from unittest import mock

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
import function_size_screen as screen  # noqa: E402

MIN = 56
BODY = "".join(f"  x += {i};\n" for i in range(59))  # with its braces' lines: 61 lines


def flagged(source):
    return screen.long_function_blocks(source, MIN)


class FunctionBodies(unittest.TestCase):
    def test_a_free_function(self):
        self.assertEqual(flagged("int f(int x) {\n" + BODY + "}\n"), [(1, 61)])

    def test_a_member_function_defined_in_its_class(self):
        src = "struct S {\n  int f() const noexcept {\n" + BODY + "  }\n};\n"
        self.assertEqual(flagged(src), [(2, 62)])

    def test_a_constructor_after_its_brace_member_initializers(self):
        src = "S::S(int a) : a_{a}, b_{0}, c_(1) {\n" + BODY + "}\n"
        self.assertEqual(flagged(src), [(1, 61)])

    def test_a_constructor_whose_last_initializer_is_a_lambda(self):
        src = "S::S() : f_([this] { return 1; }), b_{2} {\n" + BODY + "}\n"
        self.assertEqual(flagged(src), [(1, 61)])

    def test_lambdas_at_namespace_scope(self):
        for head in ("const auto f = [] {", "const auto f = [](int x) {",
                     "auto f = [&x]() mutable -> int {"):
            with self.subTest(head=head):
                self.assertEqual(flagged(head + "\n" + BODY + "};\n"), [(1, 61)])

    def test_a_trailing_return_type_or_a_macro_after_the_parameters(self):
        for head in ("auto f() -> std::vector<int> {", "auto f() -> int {",
                     "void f() STEPMOD_NOEXCEPT {", "void f() try {",
                     "template <typename T> requires C<T> void f(T t) {"):
            with self.subTest(head=head):
                self.assertEqual(flagged(head + "\n" + BODY + "}\n"), [(1, 61)])

    def test_an_operator_and_a_function_after_a_class_and_a_table(self):
        src = ("struct A { int a; };\nconstexpr int kT[] = {1, 2};\n"
               "bool operator()(int) const& {\n" + BODY + "}\n")
        self.assertEqual(flagged(src), [(3, 63)])


class NotFunctions(unittest.TestCase):
    def test_namespaces_classes_enums_and_extern_c(self):
        for head in ("namespace stepmod::ipc {", "namespace {", "class Axis final : public Base {",
                     "template <typename T> struct S : Base<decltype(T{})> {",
                     "[[nodiscard]] struct S {", "enum class E : std::uint8_t {",
                     'extern "C" {', "union {"):
            with self.subTest(head=head):
                self.assertEqual(flagged(head + "\n" + BODY.replace("+=", "=") + "};\n"), [])

    def test_tables(self):
        rows = "".join(f"    {{{i}, \"row {{ {i}\"}},\n" for i in range(59))
        for head in ("constexpr std::array<Row, 59> kRows{{", "const Row kRows[] = {{",
                     "const Row kRows[59] {{", "static const std::map<int, Row> kMap = {{"):
            with self.subTest(head=head):
                self.assertEqual(flagged(head + "\n" + rows + "}};\n"), [])

    def test_a_class_of_short_members(self):
        members = "".join(f"  int f{i}() const {{ return {i}; }}\n" for i in range(59))
        self.assertEqual(flagged("class C {\n" + members + "};\n"), [])


class Lexing(unittest.TestCase):
    def test_braces_in_comments_literals_and_directives_are_not_braces(self):
        noise = ('  auto s = "{{{"; char c = \'{\'; int n = 1\'000\'000; // {\n'
                 '  /* { { */ auto r = R"x({ ")} )x"; auto w = u8"}";\n'
                 "#define OPEN {\n#define LONG \\\n  {\n")
        src = "int g() {\n" + noise + "  return 0;\n}\nint f() {\n" + BODY + "}\n"
        first = src.count("\n", 0, src.index("int f()")) + 1
        self.assertEqual(flagged(src), [(first, first + 60)])

    def test_a_short_function_is_not_flagged(self):
        self.assertEqual(flagged("int f() {\n" + BODY[:200] + "}\n"), [])

    def test_unbalanced_braces_flag_the_whole_file(self):
        src = "int f() {\n#if A\n  if (a) {\n#else\n  if (b) {\n#endif\n  }\n}\n"
        self.assertEqual(flagged(src), [(1, 0)])
        self.assertEqual(flagged("}\n"), [(1, 0)])


class ChoosingUnits(unittest.TestCase):
    def run_main(self, tmp, deps):
        out, err = io.StringIO(), io.StringIO()
        argv = ["screen", "--root", tmp, "--build", tmp, "--min-lines", str(MIN),
                os.path.join(tmp, "a.cpp"), os.path.join(tmp, "b.cpp")]
        with mock.patch.object(sys, "argv", argv), \
                mock.patch.object(screen, "unit_dependencies", return_value=deps), \
                redirect_stdout(out), redirect_stderr(err):
            self.assertEqual(screen.main(), 0)
        return out.getvalue().split(), err.getvalue()

    def test_a_long_function_in_a_header_is_checked_through_one_unit(self):
        import tempfile
        with tempfile.TemporaryDirectory() as tmp:
            tmp = os.path.realpath(tmp)
            files = {"a.cpp": "int a() { return 1; }\n", "b.cpp": "int b() { return 2; }\n",
                     "h.hpp": "inline int h() {\n" + BODY + "}\n"}
            for name, text in files.items():
                with open(os.path.join(tmp, name), "w") as f:
                    f.write(text)
            a, b, h = (os.path.join(tmp, n) for n in ("a.cpp", "b.cpp", "h.hpp"))
            chosen, _ = self.run_main(tmp, {a: [a, h], b: [b, h]})
            self.assertEqual(chosen, [a])
            chosen, _ = self.run_main(tmp, {a: [a], b: [b]})
            self.assertEqual(chosen, [])
            chosen, err = self.run_main(tmp, {a: [a, h]})  # b.cpp not built: no log for it
            self.assertEqual(chosen, [a, b])
            self.assertIn("no dependency log for 1 of 2 units", err)
            chosen, _ = self.run_main(tmp, {a: [a]})  # b parsed whole; h reached only through b
            self.assertEqual(chosen, [b])
            chosen, _ = self.run_main(tmp, None)  # no log at all (not ninja, not built)
            self.assertEqual(chosen, [a, b])


if __name__ == "__main__":
    unittest.main()
