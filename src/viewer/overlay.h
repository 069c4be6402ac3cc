// Text over the rendered image: translucent boxes of text (stats, status, errors) and the key
// list (H), in DejaVu through SDL2_ttf, sized in pixels so that HiDPI text is sharp.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sdl_support.h"

namespace tessera::viewer {

class TextOverlay {
 public:
  // Opens the font at the 1:1 size; false (TTF_GetError says why) if it cannot be opened.
  bool open(const std::filesystem::path& font_path);
  // The text size for a display of `pixel_scale` framebuffer pixels per window point.
  void setScale(float pixel_scale);
  int fontSize() const { return base_size_; }

  // `text` (lines, wrapped at wrap_width) in a translucent box whose top left (or bottom left,
  // from_bottom) is at (x, y). Returns the box's height (0 when nothing was drawn).
  int drawTextBox(SDL_Renderer* renderer, const std::string& text, int x, int y, bool from_bottom,
                   SDL_Color color, int wrap_width);
  // The lines in two aligned columns, in a box centred on a width x height framebuffer, in the
  // largest size up to fontSize() at which they fit.
  void drawTable(SDL_Renderer* renderer,
                 const std::vector<std::pair<std::string, std::string>>& rows, int width,
                 int height);

 private:
  TTF_Font* font(int size);
  void drawBox(SDL_Renderer* renderer, SDL_Surface* surface, int x, int y);

  std::filesystem::path font_path_;
  std::map<int, SdlPtr<TTF_Font>> fonts_;  // by size in pixels; a handful at most
  int base_size_ = 15;
};

}  // namespace tessera::viewer
