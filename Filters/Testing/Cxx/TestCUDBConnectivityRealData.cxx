// Component counts of real volumes and images through vtkCUDBConnectivity, for both
// connectivities, against the counts listed in the shared data's MANIFEST.md (computed there
// with scipy.ndimage.label). Cases whose file is absent are skipped; the test is skipped
// when none is present.
#include "vtkCUDBConnectivity.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkPNGReader.h"
#include "vtkSmartPointer.h"

#include <fstream>
#include <iostream>
#include <string>

namespace
{

struct Case
{
  const char* file;
  double lower, upper;
  vtkIdType face, vertex; ///< 6/26 (3D) or 4/8 (2D) component counts
};

vtkSmartPointer<vtkImageReader2> readerFor(const std::string& path)
{
  vtkSmartPointer<vtkImageReader2> reader;
  if (path.size() > 4 && path.substr(path.size() - 4) == ".png")
    reader = vtkSmartPointer<vtkPNGReader>::New();
  else if (path.find(".nii") != std::string::npos)
    reader = vtkSmartPointer<vtkNIFTIImageReader>::New();
  else
    reader = vtkSmartPointer<vtkNrrdReader>::New();
  reader->SetFileName(path.c_str());
  return reader;
}

vtkIdType regions(vtkCUDBConnectivity* f)
{
  return static_cast<vtkIdType>(
    f->GetOutput()->GetFieldData()->GetArray("NumberOfRegions")->GetTuple1(0));
}

} // namespace

int TestCUDBConnectivityRealData(int, char*[])
{
  const double inf = VTK_DOUBLE_MAX;
  const Case cases[] = {
    { "/aneurism/aneurism_256x256x256_uint8.nhdr", 55, inf, 1939, 844 },
    { "/engine/engine_256x256x128_uint8.nhdr", 55, inf, 1, 1 },
    { "/engine/engine_256x256x128_uint8.nhdr", 130, inf, 60, 5 },
    { "/lobster/lobster_301x324x56_uint8.nhdr", 40, inf, 142, 46 },
    { "/berea/berea_200x200x200_uint8.nhdr", 0, 0, 328, 259 },
    { "/headsq/headsq_quarter_64x64x93_int16le.nhdr", 500, inf, 8, 2 },
    { "/headsq/headsq_quarter_64x64x93_int16le.nhdr", 1150, inf, 64, 22 },
    { "/dgtal_al/dgtal_al_100x100x100_uint8.nhdr", 1, 1, 1, 1 },
    { "/mricron/brodmann.nii.gz", 1, inf, 21, 8 },
    { "/mricron/aal.nii.gz", 1, inf, 1, 1 },
    // 2D: black pixels (value 0; component 0 of palette images), threshold rules as listed.
    { "/2d/jbigkit/ccitt1.png", 0, 0, 972, 945 },
    { "/2d/jbigkit/ccitt4.png", 0, 0, 4142, 4089 },
    { "/2d/jbigkit/ccitt7.png", 0, 0, 3946, 3362 },
    { "/2d/jbigkit/ccitt8.png", 0, 0, 367, 353 },
    { "/2d/jbigkit/test-t82.png", 0, 0, 278445, 167246 },
    { "/2d/leptonica/rabi.png", 0, 0, 98981, 21478 },
    { "/2d/mazes/perfect4k.png", 0, 0, 2, 2 },
    { "/2d/mazes/combo6k.png", 0, 0, 642115, 642115 },
    { "/2d/pollen/misc_pollen_sem.png", 76, inf, 1903, 1503 },
    { "/2d/skimage/page.png", -inf, 157, 289, 230 },
    { "/2d/skimage/coins.png", 108, inf, 154, 96 },
  };
  int failures = 0, found = 0;
  for (const Case& c : cases)
  {
    const std::string path = std::string(VOXELBREP_DATA_DIR) + c.file;
    if (!std::ifstream(path))
      continue;
    ++found;
    vtkSmartPointer<vtkImageReader2> reader = readerFor(path);
    reader->Update();
    vtkNew<vtkCUDBConnectivity> f;
    f->SetInputConnection(reader->GetOutputPort());
    f->SetSelectionModeToRange();
    f->SetLowerThreshold(c.lower);
    f->SetUpperThreshold(c.upper);
    f->GenerateBoxesOff(); // counts only (the boxes are checked on random volumes)
    for (int connectivity : { vtkCUDBConnectivity::FACE, vtkCUDBConnectivity::VERTEX })
    {
      f->SetConnectivity(connectivity);
      f->Update();
      const vtkIdType expected = connectivity == vtkCUDBConnectivity::FACE ? c.face : c.vertex;
      const vtkIdType got = regions(f);
      std::cout << c.file << " [" << c.lower << ", " << c.upper << "] "
                << f->GetConnectivityAsString() << ": " << got << " regions, "
                << f->GetOutput()->GetFieldData()->GetArray("NumberOfBoxes")->GetTuple1(0)
                << " boxes" << std::endl;
      if (got != expected)
      {
        std::cerr << c.file << ": expected " << expected << " regions" << std::endl;
        ++failures;
      }
    }
  }
  if (found == 0)
  {
    std::cout << "no data under " << VOXELBREP_DATA_DIR << ": skipped" << std::endl;
    return 77; // VTK_SKIP_RETURN_CODE
  }
  return failures == 0 ? 0 : 1;
}
