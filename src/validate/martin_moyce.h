// Reference data for the dam-break validation: the surge front of a collapsing water column.
//
// Source: J. C. Martin and W. J. Moyce, "Part IV. An experimental study of the collapse of
// liquid columns on a rigid horizontal plane", Phil. Trans. R. Soc. Lond. A 244 (882), 312-324
// (1952), Figure 3: column of width a = 2.25 in (57.15 mm) and height n^2 a with n^2 = 2.
// Values as digitized from that figure and distributed with PySPH
// (pysph/examples/db_exp_data.py, "mm_data_2"); facts from the literature, not code.
//
// Variables as Martin and Moyce define them: Z = z / a, the distance of the leading edge from
// the back wall over the column width, and T = n t sqrt(g / a). For n^2 = 2 this is
// T = t sqrt(2 g / a), the variable most later papers use, so the two readings agree for this
// column. (The square column, n^2 = 1, is the case asked for in issue 6; its digitized values
// were not at hand, and for it the two readings of T differ by sqrt(2), a known source of
// confusion. The n^2 = 2 column of the same paper avoids both.)
#pragma once

namespace weir {

struct SurgePoint {
    double T, Z;
};

constexpr double kMartinMoyceWidth = 2.25 * 0.0254;  // a, m
constexpr double kMartinMoyceHeightRatio = 2.0;      // n^2: height / width
constexpr SurgePoint kMartinMoyceSurge[] = {
    {0.832, 1.217}, {1.219, 1.474},  {1.997, 2.292},  {2.547, 2.995},  {3.345, 4.134},
    {4.034, 4.944}, {4.418, 5.881},  {5.091, 6.980},  {5.685, 7.945},  {6.306, 8.966},
    {6.822, 9.986}, {7.439, 10.963}, {8.031, 11.977}, {8.633, 13.005}, {9.237, 13.970},
};

}  // namespace weir
