#include "fmu/model_description.h"

#include <cstdint>
#include <sstream>
#include <vector>

#include "fmu/variables.h"

namespace wrc::fmu {
namespace {

const char* CausalityName(Causality c) {
  switch (c) {
    case Causality::kIndependent:
      return "independent";
    case Causality::kParameter:
      return "parameter";
    case Causality::kInput:
      return "input";
    case Causality::kOutput:
      return "output";
  }
  return "";
}

// Parameters are fixed (the tables load once); the flags and status are discrete outputs.
const char* Variability(const Variable& v) {
  if (v.causality == Causality::kParameter) return "fixed";
  return v.type == Type::kInt32 ? "discrete" : "continuous";
}

void WriteUnits(std::ostream& x) {
  x << "  <UnitDefinitions>\n"
       "    <Unit name=\"s\"><BaseUnit s=\"1\"/></Unit>\n"
       "    <Unit name=\"m\"><BaseUnit m=\"1\"/></Unit>\n"
       "    <Unit name=\"m/s\"><BaseUnit m=\"1\" s=\"-1\"/></Unit>\n"
       "    <Unit name=\"rad\"><BaseUnit rad=\"1\"/></Unit>\n"
       "    <Unit name=\"rad/s\"><BaseUnit s=\"-1\" rad=\"1\"/></Unit>\n"
       "    <Unit name=\"N\"><BaseUnit kg=\"1\" m=\"1\" s=\"-2\"/></Unit>\n"
       "    <Unit name=\"N.m\"><BaseUnit kg=\"1\" m=\"2\" s=\"-2\"/></Unit>\n"
       "  </UnitDefinitions>\n";
}

// The interpolation parameter's enumeration: an EnumerationType in FMI 3.0, a SimpleType in 2.0.
void WriteTypes(std::ostream& x, int version) {
  const char* items =
      "      <Item name=\"linear\" value=\"1\" description=\"multilinear, C0\"/>\n"
      "      <Item name=\"cubic\" value=\"2\" description=\"cubic Hermite, C1\"/>\n";
  x << "  <TypeDefinitions>\n";
  if (version == 3) {
    x << "    <EnumerationType name=\"Interpolation\">\n" << items << "    </EnumerationType>\n";
  } else {
    x << "    <SimpleType name=\"Interpolation\">\n      <Enumeration>\n"
      << items << "      </Enumeration>\n    </SimpleType>\n";
  }
  x << "  </TypeDefinitions>\n";
}

void WriteLogCategories(std::ostream& x) {
  x << "  <LogCategories>\n"
       "    <Category name=\"logStatusError\" description=\"Refused calls and failed lookups\"/>\n"
       "    <Category name=\"logStatusWarning\"/>\n"
       "  </LogCategories>\n";
}

void WriteVariable(std::ostream& x, const Variable& v, const StartValues& start) {
  x << "    <" << TypeName(v.type) << " name=\"" << XmlEscape(v.name) << "\" valueReference=\""
    << v.value_reference << "\" description=\"" << XmlEscape(v.description) << "\" causality=\""
    << CausalityName(v.causality) << "\" variability=\"" << Variability(v) << '"';
  if (v.type == Type::kEnumeration) x << " declaredType=\"Interpolation\"";
  if (*v.unit != '\0') x << " unit=\"" << v.unit << '"';
  const auto s = start.find(v.value_reference);
  if (s == start.end() || v.type != Type::kString) {
    if (s != start.end()) x << " start=\"" << XmlEscape(s->second) << '"';
    x << "/>\n";
    return;
  }
  x << ">\n      <Start value=\"" << XmlEscape(s->second) << "\"/>\n    </String>\n";
}

// FMI 2.0: a ScalarVariable with a typed child; Int32 is Integer, a start value on the child.
void WriteScalarVariable(std::ostream& x, const Variable& v, const StartValues& start) {
  x << "    <ScalarVariable name=\"" << XmlEscape(v.name) << "\" valueReference=\""
    << v.value_reference << "\" description=\"" << XmlEscape(v.description) << "\" causality=\""
    << CausalityName(v.causality) << "\" variability=\"" << Variability(v) << "\">\n      <";
  switch (v.type) {
    case Type::kFloat64:
      x << "Real";
      break;
    case Type::kInt32:
      x << "Integer";
      break;
    case Type::kString:
      x << "String";
      break;
    case Type::kEnumeration:
      x << "Enumeration declaredType=\"Interpolation\"";
      break;
  }
  if (*v.unit != '\0') x << " unit=\"" << v.unit << '"';
  const auto s = start.find(v.value_reference);
  if (s != start.end()) x << " start=\"" << XmlEscape(s->second) << '"';
  x << "/>\n    </ScalarVariable>\n";
}

// Outputs and initial unknowns: by value reference in FMI 3.0, by 1-based position in 2.0
// (the value reference plus one, as the variables are in value-reference order).
void WriteStructure(std::ostream& x, int version) {
  std::vector<std::uint32_t> outputs;
  for (const Variable& v : Variables()) {
    if (v.causality == Causality::kOutput) outputs.push_back(v.value_reference);
  }
  x << "  <ModelStructure>\n";
  if (version == 3) {
    for (const auto vr : outputs) x << "    <Output valueReference=\"" << vr << "\"/>\n";
    for (const auto vr : outputs) x << "    <InitialUnknown valueReference=\"" << vr << "\"/>\n";
  } else {
    for (const char* list : {"Outputs", "InitialUnknowns"}) {
      x << "    <" << list << ">\n";
      for (const auto vr : outputs) x << "      <Unknown index=\"" << vr + 1 << "\"/>\n";
      x << "    </" << list << ">\n";
    }
  }
  x << "  </ModelStructure>\n";
}

}  // namespace

std::string XmlEscape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        const bool control = static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n';
        out += control ? ' ' : c;
    }
  }
  return out;
}

std::string ModelDescriptionXml(const StartValues& start, const ModelDescriptionInfo& info) {
  const int version = info.fmi_version;
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<fmiModelDescription fmiVersion=\"" << (version == 3 ? "3.0" : "2.0")
    << "\" modelName=\"wrc wheelset\" " << (version == 3 ? "instantiationToken" : "guid") << "=\""
    << kInstantiationToken << "\" description=\"" << XmlEscape(info.description)
    << "\" generationTool=\"" << XmlEscape(info.generation_tool) << "\" generationDateAndTime=\""
    << info.generated_at << "\" variableNamingConvention=\"structured\">\n"
    << "  <CoSimulation modelIdentifier=\"" << kModelIdentifier
    << "\" canHandleVariableCommunicationStepSize=\"true\"/>\n";
  WriteUnits(x);
  WriteTypes(x, version);
  WriteLogCategories(x);
  x << "  <DefaultExperiment startTime=\"0\" stopTime=\"2\" stepSize=\"0.001\"/>\n"
    << "  <ModelVariables>\n";
  for (const Variable& v : Variables()) {
    if (version == 3) {
      WriteVariable(x, v, start);
    } else {
      WriteScalarVariable(x, v, start);
    }
  }
  x << "  </ModelVariables>\n";
  WriteStructure(x, version);
  x << "</fmiModelDescription>\n";
  return x.str();
}

}  // namespace wrc::fmu
