#include "shanshui/pigment/palette.h"

#include "shanshui/core/error.h"

namespace shanshui::pigment {

const std::vector<NamedPigment>& palette() {
  static const std::vector<NamedPigment> p = {
      {"ochre",
       "赭石 zheshi, red-brown earth for rock and the foot of mountains (qianjiang style)",
       {{0.80, 0.62, 0.42}, {0.20, 0.13, 0.07}}},
      {"indigo",
       "花青 huaqing, transparent plant blue for distant ranges and foliage",
       {{0.48, 0.58, 0.68}, {0.04, 0.06, 0.09}}},
      {"azurite",
       "石青 shiqing, opaque mineral blue of the blue-green style",
       {{0.36, 0.58, 0.74}, {0.22, 0.36, 0.50}}},
      {"malachite",
       "石绿 shilü, opaque mineral green of the blue-green style",
       {{0.44, 0.68, 0.54}, {0.24, 0.42, 0.32}}},
      {"cinnabar",
       "朱砂 zhusha, opaque red for seals, figures and autumn leaves",
       {{0.84, 0.32, 0.24}, {0.36, 0.09, 0.06}}},
      {"gamboge", "藤黄 tenghuang, transparent yellow, mixed into greens", {{0.93, 0.82, 0.36}, {0.10, 0.09, 0.02}}},
      {"ink", "墨 mo, carbon ink as a wash", {{0.30, 0.30, 0.31}, {0.02, 0.02, 0.02}}},
  };
  return p;
}

const Pigment& named(const std::string& name) {
  std::string names;
  for (const NamedPigment& n : palette()) {
    if (name == n.name) return n.pigment;
    names += (names.empty() ? "" : ", ") + std::string(n.name);
  }
  throw makeError("pigment '", name, "': unknown; expected one of ", names);
}

}  // namespace shanshui::pigment
