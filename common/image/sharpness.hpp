#pragma once

#include <opencv2/core.hpp>

namespace kapfix {

// [grey level²] A photo's sharpness: the variance of its Laplacian (3×3 kernel
// [0 1 0; 1 −4 1; 0 1 0], borders reflected) over `region`, or over the whole image when
// `region` is empty. A colour image is taken as its grey level. Motion blur and defocus
// remove the fine detail the Laplacian responds to, so a blurred photo of the same view
// scores lower; the figure compares photos of one scene, not scenes. `region` is clipped to
// the image; 0 when nothing of it is left.
double LaplacianVariance(const cv::Mat& image, cv::Rect region = {});

}  // namespace kapfix
