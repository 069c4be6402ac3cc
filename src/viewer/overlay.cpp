#include "overlay.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <system_error>

#include <tessera/viewer/viewer.h>

namespace tessera::viewer {

namespace fs = std::filesystem;

namespace {

constexpr int kSmallestFont = 8;

}  // namespace

bool TextOverlay::open(const std::filesystem::path& font_path) {
  font_path_ = font_path;
  fonts_.clear();
  return font(base_size_) != nullptr;
}

void TextOverlay::setScale(float pixel_scale) {
  // 15 points, in pixels on a HiDPI display so that text is as sharp as the model. A size that
  // cannot be opened keeps the previous one.
  const int size = std::max(kSmallestFont, static_cast<int>(15.0f * pixel_scale + 0.5f));
  if (font(size) != nullptr) base_size_ = size;
}

TTF_Font* TextOverlay::font(int size) {
  auto found = fonts_.find(size);
  if (found != fonts_.end()) return found->second.get();
  SdlPtr<TTF_Font> opened(TTF_OpenFont(font_path_.c_str(), size));
  if (!opened) return nullptr;
  return fonts_.emplace(size, std::move(opened)).first->second.get();
}

void TextOverlay::drawBox(SDL_Renderer* renderer, SDL_Surface* surface, int x, int y) {
  SdlPtr<SDL_Texture> texture(SDL_CreateTextureFromSurface(renderer, surface));
  if (!texture) return;
  const int pad = std::max(4, base_size_ / 3);
  SDL_Rect box{x, y, surface->w + 2 * pad, surface->h + 2 * pad};
  SDL_SetRenderDrawBlendMode(renderer, SDL_BLENDMODE_BLEND);
  SDL_SetRenderDrawColor(renderer, 0, 0, 0, 170);
  SDL_RenderFillRect(renderer, &box);
  SDL_Rect dst{box.x + pad, box.y + pad, surface->w, surface->h};
  SDL_RenderCopy(renderer, texture.get(), nullptr, &dst);
}

int TextOverlay::drawTextBox(SDL_Renderer* renderer, const std::string& text, int x, int y,
                             bool from_bottom, SDL_Color color, int wrap_width) {
  TTF_Font* f = font(base_size_);
  if (text.empty() || f == nullptr) return 0;
  SdlPtr<SDL_Surface> surface(TTF_RenderUTF8_Blended_Wrapped(
      f, text.c_str(), color, static_cast<Uint32>(std::max(wrap_width, 16))));
  if (!surface) return 0;
  const int pad = std::max(4, base_size_ / 3);
  drawBox(renderer, surface.get(), x, from_bottom ? y - surface->h - 2 * pad : y);
  return surface->h + 2 * pad;
}

void TextOverlay::drawTable(SDL_Renderer* renderer,
                            const std::vector<std::pair<std::string, std::string>>& rows, int width,
                            int height) {
  if (rows.empty()) return;
  size_t key_width = 0;
  for (const auto& row : rows) key_width = std::max(key_width, row.first.size());
  std::string text;
  for (const auto& row : rows) {
    if (!text.empty()) text += "\n";
    text += row.first + std::string(key_width - row.first.size() + 2, ' ') + row.second;
  }
  // The largest size at which the whole table fits inside the margins.
  const int margin = std::max(6, base_size_ / 2);
  TTF_Font* chosen = nullptr;
  for (int size = base_size_; size >= kSmallestFont; --size) {
    chosen = font(size);
    if (chosen == nullptr) continue;
    int w = 0, h = 0;
    for (const auto& row : rows) {
      int line_w = 0;
      const std::string line =
          row.first + std::string(key_width - row.first.size() + 2, ' ') + row.second;
      TTF_SizeUTF8(chosen, line.c_str(), &line_w, nullptr);
      w = std::max(w, line_w);
    }
    h = TTF_FontLineSkip(chosen) * static_cast<int>(rows.size());
    if (w + 4 * margin <= width && h + 4 * margin <= height) break;
  }
  if (chosen == nullptr) return;
  SdlPtr<SDL_Surface> surface(
      TTF_RenderUTF8_Blended_Wrapped(chosen, text.c_str(), SDL_Color{255, 255, 255, 255}, 0));
  if (!surface) return;
  const int pad = std::max(4, base_size_ / 3);
  drawBox(renderer, surface.get(), std::max(0, (width - surface->w) / 2 - pad),
          std::max(0, (height - surface->h) / 2 - pad));
}

Expected<fs::path> findOverlayFont() {
  if (const char* forced = std::getenv("TESSERA_FONT"); forced != nullptr && *forced != '\0') {
    std::error_code ec;
    if (fs::is_regular_file(forced, ec)) return fs::path(forced);
    return makeError(std::string("TESSERA_FONT names no font file: ") + forced);
  }
  const char* folders[] = {"/usr/share/fonts/truetype/dejavu", "/usr/share/fonts/dejavu",
                           "/usr/share/fonts/TTF", "/usr/local/share/fonts",
                           "/usr/share/fonts/truetype"};
  const char* names[] = {"DejaVuSansMono.ttf", "DejaVuSans.ttf"};
  std::string looked;
  for (const char* name : names) {
    for (const char* folder : folders) {
      const fs::path candidate = fs::path(folder) / name;
      std::error_code ec;
      if (fs::is_regular_file(candidate, ec)) return candidate;
    }
  }
  for (const char* folder : folders) looked += std::string(looked.empty() ? "" : ", ") + folder;
  return makeError(
      "no DejaVu font for the overlay (looked for DejaVuSansMono.ttf and DejaVuSans.ttf in " +
      looked + "); install fonts-dejavu-core or set TESSERA_FONT to a .ttf file");
}

}  // namespace tessera::viewer
