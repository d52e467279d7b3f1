// Deck validation (issue: foundation, item 4): an unknown or misspelled parameter, a wrong type, an
// out-of-range value, an invalid choice, a missing or malformed deck must each give one clear message naming
// the file, the parameter path and the valid choices. The expected texts below are the contract.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "shellfrac/core/deck_structure.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parameters.hpp"
#include "shellfrac/core/printable_text.hpp"

using namespace shellfrac;

namespace {

Teuchos::RCP<Teuchos::ParameterList> valid_section() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Section"));
  pl->set("Thickness", 0.1, "Shell thickness h [length]", params::positive_double());
  pl->set("Poisson's Ratio", 0.3, "Poisson's ratio", params::double_range(-1.0, 0.5, true, true));
  pl->set("Layers", 1, "Number of layers", params::int_range(1, 10));
  params::set_choice(*pl, "Model", "Elastic", "Constitutive model", {"Elastic", "Resultant Plasticity"});
  pl->sublist("Extra", false, "A nested sublist");
  return pl;
}

std::string error_of(Teuchos::ParameterList user) {
  try {
    params::validate(user, *valid_section(), {"deck.xml", "shellfrac->Section"});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "message:\n  " << text << "\nshould contain:\n  " << part;
}

}  // namespace

TEST(Parameters, MisspelledNameIsNamedWithSuggestionAndValidNames) {
  Teuchos::ParameterList user;
  user.set("Thicknes", 0.2);
  const auto msg = error_of(user);
  expect_contains(msg, "deck.xml: unknown parameter 'Thicknes' in 'shellfrac->Section'.");
  expect_contains(msg, "Did you mean 'Thickness'?");
  expect_contains(msg, "Valid names here: 'Thickness', 'Poisson's Ratio', 'Layers', 'Model', 'Extra' (sublist).");
}

TEST(Parameters, WrongTypeIsRejected) {
  Teuchos::ParameterList user;
  user.set("Thickness", std::string("thin"));
  expect_contains(error_of(user), "deck.xml: parameter 'shellfrac->Section->Thickness' has type string but must have type double.");
  Teuchos::ParameterList sub;
  sub.set("Extra", 3);
  expect_contains(error_of(sub), "'shellfrac->Section->Extra' has type int but must have type ParameterList");
}

TEST(Parameters, IntegerGivenForDoubleIsAccepted) {
  Teuchos::ParameterList user;
  user.set("Thickness", 2);
  EXPECT_EQ(error_of(user), "");
  params::validate(user, *valid_section(), {"deck.xml", "Section"});
  EXPECT_EQ(user.get<double>("Thickness"), 2.0);
}

TEST(Parameters, OutOfRangeNamesValueAndRange) {
  Teuchos::ParameterList neg;
  neg.set("Thickness", -0.1);
  const auto msg = error_of(neg);
  expect_contains(msg, "deck.xml: invalid value '-0.1' for parameter 'shellfrac->Section->Thickness'");
  expect_contains(msg, "(Shell thickness h [length])");
  expect_contains(msg, "must be > 0");
  Teuchos::ParameterList nu;
  nu.set("Poisson's Ratio", 0.5);
  expect_contains(error_of(nu), "must be in (-1, 0.5)");
  Teuchos::ParameterList layers;
  layers.set("Layers", 0);
  expect_contains(error_of(layers), "must be in [1, 10]");
}

TEST(Parameters, InvalidChoiceListsTheChoices) {
  Teuchos::ParameterList user;
  user.set("Model", std::string("Elastc"));
  expect_contains(error_of(user), "invalid value 'Elastc' for parameter 'shellfrac->Section->Model' (Constitutive model): "
                                  "valid choices are 'Elastic' 'Resultant Plasticity'.");
}

TEST(Parameters, DefaultsAreFilledIn) {
  Teuchos::ParameterList user;
  user.set("Layers", 3);
  params::validate(user, *valid_section(), {"deck.xml", "Section"});
  EXPECT_EQ(user.get<double>("Thickness"), 0.1);
  EXPECT_EQ(user.get<std::string>("Model"), "Elastic");
  EXPECT_EQ(user.get<int>("Layers"), 3);
}

TEST(Parameters, MissingAndMalformedDecks) {
  try {
    params::read_deck("no_such_deck.xml");
    FAIL();
  } catch (const InputError& e) {
    expect_contains(e.what(), "no_such_deck.xml: cannot open the input deck");
  }
  {
    std::ofstream("malformed_deck.xml") << "<ParameterList name=\"x\"><Parameter name=\"a\" type=\"double\" value=\"1\">";
  }
  try {
    params::read_deck("malformed_deck.xml");
    FAIL();
  } catch (const InputError& e) {
    expect_contains(e.what(), "malformed_deck.xml: not a valid Teuchos XML parameter list");
  }
}

// Hostile input (docs/hostile_input.md): Teuchos keeps whatever prefix of a number it can read, silently:
// "0.01mm" was 0.01, "zero point three" was 0, an int "10.7" was 10, "99999999999999" was 276447231 and
// "{0, x, 1}" was {0, 0, 1}. read_deck now refuses every numeric value that is not a whole number of its type.
TEST(Parameters, NumbersMustBeWholeNumbersOfTheirType) {
  struct Case {
    std::string type, value, message;
  };
  const std::vector<Case> cases = {
      {"double", "0.01mm", "parameter 'x->a' (type double): the value '0.01mm' is not a number"},
      {"double", "zero point three", "the value 'zero point three' is not a number"},
      {"double", "0x10", "the value '0x10' is not a number"},
      {"double", "1e400", "the value '1e400' is not a number"},
      {"int", "10.7", "(type int): the value '10.7' is not an integer in [-2147483648, 2147483647]"},
      {"int", "99999999999999", "the value '99999999999999' is not an integer"},
      {"int", "+-5", "the value '+-5' is not an integer"},
      {"Array(double)", "{0.0, x, 1.0}", "(type Array(double)): the element 'x' of '{0.0, x, 1.0}' is not a number"},
      {"Array(int)", "{1, 2.5}", "the element '2.5' of '{1, 2.5}' is not an integer"},
      // A non-finite array element used to pass (no validator sees array elements) and act as 0.
      {"Array(double)", "{0, 0, nan}", "the element 'nan' of '{0, 0, nan}' is not a finite number"},
      {"Array(double)", "{inf}", "the element 'inf' of '{inf}' is not a finite number"},
      {"Array(double)", "{1, -Infinity, 2}", "the element '-Infinity' of '{1, -Infinity, 2}' is not a finite number"},
  };
  for (const auto& c : cases) {
    {
      std::ofstream("numbers_deck.xml") << "<ParameterList name=\"x\"><Parameter name=\"a\" type=\"" << c.type
                                        << "\" value=\"" << c.value << "\"/></ParameterList>\n";
    }
    try {
      params::read_deck("numbers_deck.xml");
      ADD_FAILURE() << c.type << " '" << c.value << "' was accepted";
    } catch (const InputError& e) {
      expect_contains(e.what(), "numbers_deck.xml: ");
      expect_contains(e.what(), c.message);
    }
  }
  // Whole numbers, with blanks, signs, exponents, nan / inf (the range validators reject those) still pass.
  {
    std::ofstream("numbers_ok_deck.xml")
        << "<ParameterList name=\"x\"><Parameter name=\"a\" type=\"double\" value=\" -2.5e-3 \"/>"
           "<Parameter name=\"b\" type=\"int\" value=\"+7\"/><Parameter name=\"c\" type=\"double\" value=\"nan\"/>"
           "<Parameter name=\"d\" type=\"Array(double)\" value=\"{1, 2.0, -3e2}\"/>"
           "<Parameter name=\"e\" type=\"Array(double)\" value=\"{}\"/>"
           "<ParameterList name=\"s\"><Parameter name=\"f\" type=\"int\" value=\"-2147483648\"/></ParameterList>"
           "</ParameterList>\n";
  }
  const auto deck = params::read_deck("numbers_ok_deck.xml");
  EXPECT_EQ(deck->get<double>("a"), -2.5e-3);
  EXPECT_EQ(deck->get<int>("b"), 7);
  EXPECT_EQ(deck->sublist("s").get<int>("f"), -2147483648LL);
}

TEST(Parameters, TeuchosParseErrorsAreOneLineWithoutTeuchosInternals) {
  { std::ofstream("truncated_deck.xml") << "<ParameterList name=\"x\">\n<Parameter name=\"a\" type=\"int\" value=\"1\"/>\n<Para"; }
  try {
    params::read_deck("truncated_deck.xml");
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    expect_contains(msg, "truncated_deck.xml: not a valid Teuchos XML parameter list: XML parse error at line 3");
    EXPECT_EQ(msg.find("Throw"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

namespace {
std::string read_deck_error(const std::string& file) {
  try {
    params::read_deck(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

// Hostile input (docs/hostile_input.md): 10 000 nested sublists overflowed the stack in the XML conversion; the
// nesting is limited before the parser sees it, and 64 levels still pass.
TEST(Parameters, DeepNestingIsRefusedWithItsLine) {
  const auto nested = [](int depth) {
    std::string text = "<ParameterList name=\"x\">\n";
    for (int i = 1; i < depth; ++i) text += "<ParameterList name=\"a\">\n";
    for (int i = 0; i < depth; ++i) text += "</ParameterList>\n";
    return text;
  };
  { std::ofstream("deep_deck.xml") << nested(10000); }
  EXPECT_EQ(read_deck_error("deep_deck.xml"),
            "deep_deck.xml: line 65: the XML elements are nested more than 64 levels deep (a deck needs only a few "
            "levels of sublists)");
  { std::ofstream("deep_ok_deck.xml") << nested(params::max_deck_nesting); }
  EXPECT_EQ(read_deck_error("deep_ok_deck.xml"), "");
}

// Teuchos keeps the last of two entries with one name, silently. Both lines are named; comments, CDATA and the
// same name in another sublist do not count.
TEST(Parameters, EntriesGivenTwiceAreRefusedWithBothLines) {
  {
    std::ofstream("twice_deck.xml") << "<ParameterList name=\"x\">\n"
                                       "  <Parameter name=\"a\" type=\"int\" value=\"1\"/>\n"
                                       "  <!-- <Parameter name=\"b\" type=\"int\" value=\"1\"/> -->\n"
                                       "  <ParameterList name=\"s\"><Parameter name=\"a\" type=\"int\" value=\"1\"/>\n"
                                       "    <Parameter name=\"b\" type=\"int\" value=\"1\"/></ParameterList>\n"
                                       "  <Parameter name = 'b' type=\"int\" value=\"2\"/>\n"
                                       "  <Parameter type=\"int\" value=\"3\"\n name=\"a\"/>\n"
                                       "</ParameterList>\n";
  }
  EXPECT_EQ(read_deck_error("twice_deck.xml"),
            "twice_deck.xml: 'x->a' is given twice, on lines 2 and 7 (only the last would count); give each "
            "parameter or sublist once");
  {
    std::ofstream("twice_list_deck.xml") << "<ParameterList name=\"x\">\n<ParameterList name=\"s\"/>\n"
                                            "<ParameterList name=\"t\">\n<ParameterList name=\"s\"/>\n"
                                            "</ParameterList>\n<ParameterList name=\"s\">\n</ParameterList>\n"
                                            "</ParameterList>\n";
  }
  EXPECT_EQ(read_deck_error("twice_list_deck.xml"),
            "twice_list_deck.xml: 'x->s' is given twice, on lines 2 and 6 (only the last would count); give each "
            "parameter or sublist once");
}

// /dev/zero was read to 2.1 GB before the program died: a deck must be a regular file (a FIFO would block in
// open()), of at most 16 MiB, measured before it is read.
TEST(Parameters, DeckSizeIsLimitedBeforeReading) {
  EXPECT_EQ(read_deck_error("/dev/zero"),
            "/dev/zero: the input deck is a device, not a regular file; name the file itself");
  EXPECT_EQ(read_deck_error("."), ".: is a directory, not an input deck");
  { std::ofstream("huge_deck.xml").seekp(params::max_deck_bytes) << ' '; }
  EXPECT_EQ(read_deck_error("huge_deck.xml"),
            "huge_deck.xml: the input deck has 16777217 bytes, more than the 16 MiB a deck may have");
  std::remove("huge_deck.xml");
}

// A double without a range of its own (a pressure, a normal velocity) must still be finite.
TEST(Parameters, DoublesWithoutARangeMustBeFinite) {
  Teuchos::ParameterList valid("Load");
  valid.set("Pressure", 0.0, "p0 [force/length^2]");
  for (double bad : {std::numeric_limits<double>::infinity(), std::nan("")}) {
    Teuchos::ParameterList user;
    user.set("Pressure", bad);
    try {
      params::validate(user, valid, {"deck.xml", "shellfrac->Loads->blast"});
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      expect_contains(e.what(), "deck.xml: invalid value '");
      expect_contains(e.what(), "' for parameter 'shellfrac->Loads->blast->Pressure' (p0 [force/length^2]): value ");
      expect_contains(e.what(), " is out of range: must be finite");
    }
  }
  Teuchos::ParameterList user;
  user.set("Pressure", -1e300);
  params::validate(user, valid, {"deck.xml", "shellfrac->Loads->blast"});
}

// Names and text values go into Exodus files and messages: printable UTF-8 only.
TEST(Parameters, NamesAndTextMustBePrintableUtf8) {
  EXPECT_EQ(params::unprintable_part("plain name 12"), "");
  EXPECT_EQ(params::unprintable_part("Stahl \xc3\xa4 \xe2\x82\xac \xf0\x9f\x94\xa9"), "");  // a-umlaut, euro, emoji
  EXPECT_EQ(params::unprintable_part("ab\x01"), "a control character (byte 0x01) at position 3");
  EXPECT_EQ(params::unprintable_part("\x7f"), "a control character (byte 0x7f) at position 1");
  EXPECT_EQ(params::unprintable_part("a\tb"), "a control character (byte 0x09) at position 2");
  EXPECT_EQ(params::unprintable_part("caf\xe9"), "a byte that is not UTF-8 (0xe9) at position 4");       // Latin-1
  EXPECT_EQ(params::unprintable_part("\xc0\xaf"), "a byte that is not UTF-8 (0xc0) at position 1");      // overlong
  EXPECT_EQ(params::unprintable_part("\xed\xa0\x80"), "a byte that is not UTF-8 (0xed) at position 1");  // surrogate
  EXPECT_EQ(params::unprintable_part("x\xc2\x9b"), "a control character (U+009b) at position 2");
  EXPECT_EQ(params::escaped(std::string("a\x01\xe9") + "b"), "a\\x01\\xe9b");
  Teuchos::ParameterList pl;
  pl.sublist("Regions").sublist("patch").set("Shape", std::string("Box\x1b[2J"));
  try {
    params::check_printable(pl, {"deck.xml", "shellfrac"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "deck.xml: the value 'Box\\x1b[2J' of 'shellfrac->Regions->patch->Shape' has a control "
                 "character (byte 0x1b) at position 4; names and text must be printable UTF-8");
  }
}

TEST(Parameters, DocumentedSkeletonListsDefaultsChoicesAndRanges) {
  std::ostringstream os;
  params::write_documented_xml(os, *valid_section());
  const std::string xml = os.str();
  expect_contains(xml, "<!-- Shell thickness h [length]. Range: > 0. -->");
  expect_contains(xml, "<Parameter name=\"Thickness\" type=\"double\" value=\"0.10000000000000001\"/>");
  expect_contains(xml, "Choices: 'Elastic' 'Resultant Plasticity'.");
  expect_contains(xml, "<ParameterList name=\"Extra\">");
}

TEST(Parameters, EditDistance) {
  EXPECT_EQ(params::edit_distance("Thicknes", "Thickness"), 1u);
  EXPECT_EQ(params::edit_distance("", "abc"), 3u);
  EXPECT_EQ(params::edit_distance("kitten", "sitting"), 3u);
}
